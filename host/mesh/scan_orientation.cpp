#include "mesh/scan_orientation.h"

namespace mcquad {

ScanOrientation::ScanOrientation(const OrientedSample& sample) : sample_(sample), index_(sample.points) {}

bool ScanOrientation::faces_inward(const QuadMesh& mesh, int face) const {
  long nearest = index_.nearest(face_centroid(mesh, face).cast<float>()).first;
  if (nearest < 0) return false;
  Eigen::Vector3d normal = face_vector_area(mesh, mesh.face_handle(face));
  return normal.dot(sample_.normals[size_t(nearest)].cast<double>()) < 0;
}

std::vector<int> ScanOrientation::inward_faces(const QuadMesh& mesh, const std::vector<int>* candidates) const {
  long count = candidates ? long(candidates->size()) : long(mesh.n_faces());
  auto face_at = [&](long k) { return candidates ? (*candidates)[size_t(k)] : int(k); };
  std::vector<char> inward(size_t(count), 0);
#pragma omp parallel for schedule(static) if (count > 1024)
  for (long k = 0; k < count; ++k) inward[size_t(k)] = faces_inward(mesh, face_at(k));
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
