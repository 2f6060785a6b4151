#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/face_intersections.h"

namespace mcquad {

//! The intersecting face pairs of one mesh as its vertices move, step after
//! step, without a new broad phase each time: a Verlet list, as molecular
//! dynamics keeps for pairs of atoms. The list holds the triangle pairs
//! (sharing no vertex, of different faces) whose boxes were within `gap`
//! per axis at some reference positions. While no vertex has moved more
//! than about gap / 2 along any axis from there, every pair whose boxes
//! overlap now is on the list, so testing the list finds exactly what
//! intersecting_face_pairs finds; once one has, the list is built again at
//! the positions of the call. On the knot's mesh most of the evolution's
//! steps move every vertex far less than that (docs/PERFORMANCE.md).
class CloseTrianglePairs {
 public:
  explicit CloseTrianglePairs(double gap) : gap_(gap) {}

  //! As intersecting_face_pairs(triangles, only_faces); every call's
  //! triangles must have the same corners (one mesh), positions may differ.
  std::vector<std::pair<int, int>> intersecting_face_pairs(const MeshTriangles& triangles,
                                                           const std::vector<char>* only_faces = nullptr);

  //! How many times the list has been built.
  size_t builds() const { return builds_; }

 private:
  double gap_;
  std::vector<Eigen::Vector3d> reference_;       //!< positions the list was built at
  std::vector<std::pair<int, int>> candidates_;  //!< triangle pairs, a < b
  size_t builds_ = 0;

  //! Whether some vertex has gone too far from reference_ for the list.
  bool moved_too_far(const MeshTriangles& triangles) const;
  void build(const MeshTriangles& triangles);
};

}  // namespace mcquad
