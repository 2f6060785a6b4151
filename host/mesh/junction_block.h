#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <optional>
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

//! Where a block's edge vertices and two-bone corners go: as laid out
//! (edges midway between their two corners' directions), or, between the
//! faces of two bones less than kAcuteEdgeDegrees apart, toward the crotch
//! between their tubes. Midway, an acute pair's edge vertex sits off the
//! crotch and the fit leaves a notch there whose faces turn inward
//! (docs/CONSTRUCTION.md, section 3, step 6). The crotch is where the cloud
//! has it: on the arc between the bones, the direction along which the cloud
//! is nearest (nearest_on_arc); only where that is nearer than kCrotchSlack
//! times where the tubes' walls meet.
enum class BlockEdges { kMidway, kAcuteToCrotch };
constexpr double kAcuteEdgeDegrees = 75.0;
//! The cloud's crotch counts as the tubes' where the cloud along it is
//! nearer than this times where the tubes' walls meet (1.05 to 2.0 measured
//! alike on the random trees and blob-limbs).
constexpr double kCrotchSlack = 1.2;
//! The search for the crotch looks this many times farther than where the
//! tubes' walls meet on the bisector.
constexpr double kCrotchSearch = 3.0;
//! Two edges between the same two bones' faces go this far from the plane
//! through the crotch square to the bones' plane toward the crotch, not
//! both onto it. Measured on 20 random trees with the crotch on the
//! bisector (docs/HARD_CASES.md, "Acute edges toward the crotch"): 0.5 and
//! 0.8 leave 7 over 0.1 % of their area inward, 0.95 leaves 8; 0.8 turned
//! 0.15 % of the 30-degree fan's bare evolution.
constexpr double kTowardCrotch = 0.5;

//! Where the cloud's crotch between bones `u` and `v` (unit) lies seen
//! from the node, or none where the cloud has no crotch there.
using CrotchFinder = std::function<std::optional<Eigen::Vector3d>(const Eigen::Vector3d& u, const Eigen::Vector3d& v)>;

//! Directions on the arc between two bones: the search for their crotch
//! takes the middle half of them (nearer a bone a ray runs along its tube's
//! wall, or out of a thin branch's wall beside it).
constexpr int kCrotchSamples = 16;

//! A direction on the arc is the crotch instead of the bisector only where
//! the cloud along it is nearer than this times the bisector's distance.
//! Around a round body (the octopus's mantle) the cloud is as near along
//! every direction, within 0.3 %; without this the search followed that
//! noise to crotches up to 9.5 degrees off the bisector, and the octopus
//! turned 0.34 % of its area inward instead of 0.24 %. 2 % is about a
//! sample spacing of the probe there (docs/HARD_CASES.md, "The crotch
//! searched in the cloud").
constexpr double kCrotchLean = 0.98;

//! The direction on the arc from `u` to `v` (unit, less than 180 degrees
//! apart) where `distance` is least, among the middle half of
//! kCrotchSamples + 1 evenly spaced ones; the bisector unless that one is
//! nearer than kCrotchLean times the bisector's distance.
Eigen::Vector3d nearest_on_arc(const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                               const std::function<double(const Eigen::Vector3d&)>& distance);

//! The direction from the node to layout corner `corner`'s vertex: where it
//! lies between exactly two bones' faces (a doubled edge's two-sided face,
//! junction_layout.h), an acute pair's crotch as `placement` says.
Eigen::Vector3d corner_direction(const JunctionLayout& layout, const JunctionBones& bones, size_t corner,
                                 BlockEdges placement, const CrotchFinder& crotch_between);

//! The direction from the node to layout edge `edge`'s vertex (not unit).
Eigen::Vector3d edge_direction(const JunctionLayout& layout, const JunctionBones& bones, size_t edge,
                               BlockEdges placement, const CrotchFinder& crotch_between);

//! Adds the junction block laid out by `layout` (junction_layout.h) at
//! `center`: its corners and the midpoints of its edges (one Catmull-Clark
//! split; placed as `edge_placement` says) at tube_union_reach, so they sit
//! where neighbouring tubes meet, but no farther out than
//! `reach(direction, wanted)` (the cloud is not round around every
//! junction). Each bone's quad is left open: its 8-vertex ring is returned
//! as the bone's port, counter-clockwise about the port's outward direction.
//! With `closed`, the quads are filled instead (four quads round a centre
//! vertex each), so the block alone is a closed polyhedron.
std::vector<Port> add_junction_block(QuadSoup& soup, const Eigen::Vector3d& center, const JunctionLayout& layout,
                                     const JunctionBones& bones,
                                     const std::function<double(const Eigen::Vector3d&, double)>& reach,
                                     bool closed = false, BlockEdges edge_placement = BlockEdges::kMidway);

}  // namespace mcquad
