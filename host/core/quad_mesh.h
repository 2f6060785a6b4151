#pragma once

#include <Eigen/Geometry>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <vector>

namespace mcquad {

struct QuadMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::Status);
};

//! The host-side mesh used for topology work, refinement and writing.
using QuadMesh = OpenMesh::PolyMesh_ArrayKernelT<QuadMeshTraits>;

//! Regular vertex of a quad mesh: valence 4 inside, 3 on an open boundary.
inline bool is_regular_vertex(const QuadMesh& mesh, QuadMesh::VertexHandle v) {
  return mesh.valence(v) == (mesh.is_boundary(v) ? 3u : 4u);
}

//! A vertex's position as an Eigen vector.
inline Eigen::Vector3d point_of(const QuadMesh& mesh, QuadMesh::VertexHandle v) {
  const auto& p = mesh.point(v);
  return {p[0], p[1], p[2]};
}

//! A face's corners in face order.
inline std::vector<Eigen::Vector3d> face_corners(const QuadMesh& mesh, QuadMesh::FaceHandle f) {
  std::vector<Eigen::Vector3d> corners;
  for (auto v : mesh.fv_range(f)) corners.push_back(point_of(mesh, v));
  return corners;
}

//! The mean of a face's corners.
inline Eigen::Vector3d face_centroid(const QuadMesh& mesh, int face) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int corners = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) sum += point_of(mesh, v), ++corners;
  return corners ? Eigen::Vector3d(sum / corners) : sum;
}

//! Twice the vector area of a quad: the cross product of its diagonals,
//! exact for planar quads and well defined for bent ones.
inline Eigen::Vector3d quad_vector_area(const std::vector<Eigen::Vector3d>& c) {
  return (c[2] - c[0]).cross(c[3] - c[1]);
}

//! Twice the vector area of any face (the sum of its corners' cross
//! products): its normal, unnormalized. For a quad it equals
//! quad_vector_area.
inline Eigen::Vector3d face_vector_area(const QuadMesh& mesh, QuadMesh::FaceHandle f) {
  std::vector<Eigen::Vector3d> c = face_corners(mesh, f);
  if (c.size() == 4) return quad_vector_area(c);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < c.size(); ++k) sum += c[k].cross(c[(k + 1) % c.size()]);
  return sum;
}

}  // namespace mcquad
