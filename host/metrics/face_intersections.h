#pragma once

#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "core/quad_mesh.h"

namespace mcquad {

//! Whether two triangles intersect (an edge of one crosses the other).
bool triangles_intersect(const Eigen::Vector3d* a, const Eigen::Vector3d* b);

//! Distance from p to triangle (t0, t1, t2).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                               const Eigen::Vector3d& t2);

//! Pairs of faces that intersect, faces sharing a vertex excluded. Each quad
//! is split into two triangles along its 0-2 diagonal; candidates come from a
//! uniform grid over the triangles' boxes, then an exact test.
std::vector<std::pair<int, int>> intersecting_face_pairs(const QuadMesh& mesh);

}  // namespace mcquad
