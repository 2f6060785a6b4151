#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "mesh/junction_layout.h"
#include "mesh/quad_soup.h"

namespace mcquad {

//! The bones of one junction as the block sees them.
struct JunctionBones {
  std::vector<Eigen::Vector3d> directions;  //!< unit, from the node
  std::vector<double> tube_radii;           //!< the initial tube's radius on each bone
};

//! How far from the node the union of the junction's tubes reaches in
//! `direction` (unit): a tube of radius r on a bone at angle t from it ends
//! r / sin t out (its wall), or r behind the node (its round end); the union
//! is the farthest. Near a bone, 1 / sin t is capped (at 15 degrees).
double tube_union_reach(const JunctionBones& bones, const Eigen::Vector3d& direction);

//! Adds the junction block laid out by `layout` (junction_layout.h) at
//! `center`: its corners and the midpoints of its edges (one Catmull-Clark
//! split) at tube_union_reach, so they sit where neighbouring tubes meet,
//! but no farther out than `reach(direction, wanted)` (the cloud is not round
//! around every junction). Each bone's quad is left open: its 8-vertex ring is
//! returned as the bone's port, counter-clockwise about the port's outward
//! direction. With `closed`, the quads are filled instead (four quads round
//! a centre vertex each), so the block alone is a closed polyhedron.
std::vector<Port> add_junction_block(QuadSoup& soup, const Eigen::Vector3d& center, const JunctionLayout& layout,
                                     const JunctionBones& bones,
                                     const std::function<double(const Eigen::Vector3d&, double)>& reach,
                                     bool closed = false);

}  // namespace mcquad
