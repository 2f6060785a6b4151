#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/quad_mesh.h"

namespace mcquad {

//! Whether two triangles intersect (an edge of one crosses the other).
bool triangles_intersect(const Eigen::Vector3d* a, const Eigen::Vector3d* b);

//! The point of triangle (t0, t1, t2) nearest to p.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                          const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

//! Distance from p to triangle (t0, t1, t2).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0, const Eigen::Vector3d& t1,
                               const Eigen::Vector3d& t2);

//! The faces of a mesh as triangles (a quad split along its 0-2 diagonal),
//! by vertex ids into one array of positions: 16 bytes a triangle instead of
//! 72 for its corners, which matters at millions of faces.
struct MeshTriangles {
  std::vector<Eigen::Vector3d> positions;   //!< per vertex
  std::vector<std::array<int, 3>> corners;  //!< per triangle: vertex ids
  std::vector<int> face;                    //!< per triangle: the face it came from

  size_t size() const { return face.size(); }
  const Eigen::Vector3d& corner(size_t triangle, int k) const {
    return positions[size_t(corners[triangle][size_t(k)])];
  }
  Eigen::Vector3d centroid(size_t triangle) const {
    return (corner(triangle, 0) + corner(triangle, 1) + corner(triangle, 2)) / 3.0;
  }
};

MeshTriangles triangulate(const QuadMesh& mesh);
//! The same from flat quads (4 vertex ids each) and positions (3 floats each).
MeshTriangles triangulate(const std::vector<uint32_t>& quads, const std::vector<float>& positions);

//! Whether triangles a and b have a corner in common (then they touch, and
//! count as neighbours, not as crossing).
bool triangles_share_a_vertex(const MeshTriangles& triangles, size_t a, size_t b);

//! Whether triangles a and b intersect: false when they share a vertex, then
//! their boxes, then the exact test.
bool triangle_pair_intersects(const MeshTriangles& triangles, size_t a, size_t b);

//! The intersecting face pairs found by several threads: each adds its own,
//! then sorted() merges them, each pair once (a quad is two triangles, so a
//! pair of faces can be found twice).
class FacePairsFound {
 public:
  FacePairsFound();
  //! Triangles a and b intersect: their faces are a pair.
  void add(const MeshTriangles& triangles, size_t a, size_t b, int thread);
  std::vector<std::pair<int, int>> sorted() const;

 private:
  std::vector<std::vector<std::pair<int, int>>> per_thread_;
};

//! Pairs of faces that intersect, faces sharing a vertex excluded, sorted.
//! Each quad is split into two triangles along its 0-2 diagonal. Candidates
//! are the triangles whose bounding boxes overlap (found in a TriangleTree,
//! mesh/triangle_tree.h), then an exact test.
std::vector<std::pair<int, int>> intersecting_face_pairs(const QuadMesh& mesh);
//! The same on triangles; with `only_faces` (per face, nonzero = test it),
//! just the pairs with at least one of those faces.
std::vector<std::pair<int, int>> intersecting_face_pairs(const MeshTriangles& triangles,
                                                         const std::vector<char>* only_faces = nullptr);

}  // namespace mcquad
