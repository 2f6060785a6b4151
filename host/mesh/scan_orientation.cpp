#include "mesh/scan_orientation.h"

#include <array>

namespace mcquad {

ScanOrientation::ScanOrientation(const OrientedSample& sample) : sample_(sample), index_(sample.points) {}

bool ScanOrientation::against_scan(const Eigen::Vector3d& centroid, const Eigen::Vector3d& normal) const {
  long nearest = index_.nearest(centroid.cast<float>()).first;
  return nearest >= 0 && normal.dot(sample_.normals[size_t(nearest)].cast<double>()) < 0;
}

bool ScanOrientation::faces_inward(const QuadMesh& mesh, int face, FaceTest test) const {
  if (test == FaceTest::kTriangles) return inward_area(mesh, face) > 0;
  return against_scan(face_centroid(mesh, face), face_vector_area(mesh, mesh.face_handle(face)));
}

double ScanOrientation::inward_area(const QuadMesh& mesh, int face) const {
  std::array<Eigen::Vector3d, 4> corner;
  int corners = 0;
  for (auto v : mesh.fv_range(mesh.face_handle(face))) {
    if (corners == 4) {
      corners = 5;  // not a quad
      break;
    }
    const auto& p = mesh.point(v);
    corner[size_t(corners++)] = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  if (corners != 4) {
    Eigen::Vector3d normal = face_vector_area(mesh, mesh.face_handle(face));
    return against_scan(face_centroid(mesh, face), normal) ? 0.5 * normal.norm() : 0.0;
  }
  double area = 0;
  for (int t = 0; t < 2; ++t) {
    const Eigen::Vector3d &a = corner[0], &b = corner[size_t(1 + t)], &c = corner[size_t(2 + t)];
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (against_scan((a + b + c) / 3.0, normal)) area += 0.5 * normal.norm();
  }
  return area;
}

double ScanOrientation::inward_area_fraction(const QuadMesh& mesh, const std::vector<int>& faces) const {
  double total = 0, part = 0;
  for (auto f : mesh.faces()) total += 0.5 * face_vector_area(mesh, f).norm();
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
