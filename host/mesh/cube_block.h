#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <vector>

#include "mesh/quad_soup.h"

namespace mcquad {

//! The rotation (columns: block axes in world space) of a junction block and
//! which of its six face groups each bone takes: +x,-x,+y,-y,+z,-z = 0..5.
struct BlockOrientation {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  std::vector<int> face_of_bone;
  double worst_cosine = 1;  //!< smallest cosine between a bone and its face's normal
};

//! One rotation of the block for all its bones, maximizing the bones'
//! alignment with distinct face groups (sum of cosines plus the worst one).
//! Valence 1..6; UnsupportedError above.
BlockOrientation orient_cube_block(const std::vector<Eigen::Vector3d>& bone_directions);

//! Adds a cube junction block (used where the bones fit a cube, see
//! initial_mesh.cpp; junction_block.h serves any other): a cube of six face
//! groups (2x2 quads each) centred at `center`, its vertices on a sphere of
//! radius `size`, rotated by `orientation`. The face groups taken by bones
//! are left open (filled too with `closed`, to show the block alone); their
//! rings are returned as ports, in bone order.
//! `reach(direction)` bounds each vertex's distance from the centre (the
//! cloud is not round around every junction).
std::vector<Port> add_cube_block(QuadSoup& soup, const Eigen::Vector3d& center, double size,
                                 const BlockOrientation& orientation,
                                 const std::function<double(const Eigen::Vector3d&)>& reach, bool closed = false);

}  // namespace mcquad
