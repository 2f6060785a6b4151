#include "mesh/scan_orientation.h"

#include <array>
#include <optional>

namespace mcquad {

ScanOrientation::ScanOrientation(const OrientedSample& sample) : sample_(sample), index_(sample.points) {}

bool ScanOrientation::against_scan(const Eigen::Vector3d& centroid, const Eigen::Vector3d& normal) const {
  long nearest = index_.nearest(centroid.cast<float>()).first;
  return nearest >= 0 && normal.dot(sample_.normals[size_t(nearest)].cast<double>()) < 0;
}

double ScanOrientation::depth_below(const Eigen::Vector3d& p, Eigen::Vector3d* normal) const {
  long nearest = index_.nearest(p.cast<float>()).first;
  if (nearest < 0) return 0.0;
  const Eigen::Vector3d n = sample_.normals[size_t(nearest)].cast<double>();
  if (normal) *normal = n;
  return (sample_.points[size_t(nearest)].cast<double>() - p).dot(n);
}

namespace {

//! A face's corners when it is a quad.
std::optional<std::array<Eigen::Vector3d, 4>> quad_corners(const QuadMesh& mesh, int face) {
  std::array<Eigen::Vector3d, 4> corner;
  size_t corners = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) {
    if (corners == 4) return std::nullopt;
    const auto& p = mesh.point(v);
    corner[corners++] = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (corners != 4) return std::nullopt;
  return corner;
}

//! The normal (twice the area) of triangle `t` (0: corners 0 1 2, 1: 0 2 3)
//! of the split a viewer draws a quad with.
Eigen::Vector3d drawn_triangle_normal(const std::array<Eigen::Vector3d, 4>& q, int t) {
  return (q[size_t(1 + t)] - q[0]).cross(q[size_t(2 + t)] - q[0]);
}

//! The area a viewer draws of face `face`: its two triangles' for a quad.
double drawn_area(const QuadMesh& mesh, int face) {
  auto q = quad_corners(mesh, face);
  if (!q) return 0.5 * face_vector_area(mesh, mesh.face_handle(face)).norm();
  return 0.5 * (drawn_triangle_normal(*q, 0).norm() + drawn_triangle_normal(*q, 1).norm());
}

}  // namespace

bool ScanOrientation::faces_inward(const QuadMesh& mesh, int face, FaceTest test) const {
  if (test == FaceTest::kTriangles) return inward_area(mesh, face) > 0;
  return against_scan(face_centroid(mesh, face), face_vector_area(mesh, mesh.face_handle(face)));
}

double ScanOrientation::inward_area(const QuadMesh& mesh, int face) const {
  auto q = quad_corners(mesh, face);
  if (!q) return faces_inward(mesh, face, FaceTest::kWhole) ? drawn_area(mesh, face) : 0.0;
  double area = 0;
  for (int t = 0; t < 2; ++t) {
    Eigen::Vector3d normal = drawn_triangle_normal(*q, t);
    Eigen::Vector3d centroid = ((*q)[0] + (*q)[size_t(1 + t)] + (*q)[size_t(2 + t)]) / 3.0;
    if (against_scan(centroid, normal)) area += 0.5 * normal.norm();
  }
  return area;
}

double ScanOrientation::inward_area_fraction(const QuadMesh& mesh, const std::vector<int>& faces) const {
  double total = 0, part = 0;
  for (auto f : mesh.faces()) total += drawn_area(mesh, f.idx());
  for (int f : faces) part += inward_area(mesh, f);
  return total > 0 ? part / total : 0.0;
}

std::vector<int> ScanOrientation::inward_faces(const QuadMesh& mesh, const std::vector<int>* candidates,
                                               FaceTest test) const {
  long count = candidates ? long(candidates->size()) : long(mesh.n_faces());
  auto face_at = [&](long k) { return candidates ? (*candidates)[size_t(k)] : int(k); };
  std::vector<char> inward(size_t(count), 0);
#pragma omp parallel for schedule(static) if (count > 1024)
  for (long k = 0; k < count; ++k) inward[size_t(k)] = faces_inward(mesh, face_at(k), test);
  std::vector<int> faces;
  for (long k = 0; k < count; ++k)
    if (inward[size_t(k)]) faces.push_back(face_at(k));
  return faces;
}

std::vector<int> faces_against_normals(const QuadMesh& mesh, const OrientedSample& oriented) {
  return ScanOrientation(oriented).inward_faces(mesh);
}

double area_fraction(const QuadMesh& mesh, const std::vector<int>& faces) {
  auto area = [&](QuadMesh::FaceHandle f) { return 0.5 * face_vector_area(mesh, f).norm(); };
  double total = 0, part = 0;
  for (auto f : mesh.faces()) total += area(f);
  for (int f : faces) part += area(mesh.face_handle(f));
  return total > 0 ? part / total : 0.0;
}

}  // namespace mcquad
