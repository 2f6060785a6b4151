#include "metrics/inward_faces.h"

#include "core/shared_math.h"
#include "skeleton/bone_assignment.h"

namespace mcquad {

size_t inward_faces(const QuadMesh& mesh, const SkeletonGraph& skeleton) {
  return inward_face_indices(mesh, skeleton).size();
}

std::vector<int> inward_face_indices(const QuadMesh& mesh, const SkeletonGraph& skeleton) {
  std::vector<int> inward;
  std::vector<double> distance(skeleton.edges.size());
  std::vector<Eigen::Vector3d> nearest(skeleton.edges.size());
  for (auto f : mesh.faces()) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> corners;
    for (auto v : mesh.fv_range(f)) {
      const auto& p = mesh.point(v);
      corners.emplace_back(p[0], p[1], p[2]);
      centroid += corners.back();
    }
    centroid /= double(corners.size());
    Eigen::Vector3d normal = face_vector_area(mesh, f);
    double closest = INFINITY;
    for (size_t b = 0; b < skeleton.edges.size(); ++b) {
      double t;
      const auto& a = skeleton.positions[skeleton.edges[b][0]];
      const auto& c = skeleton.positions[skeleton.edges[b][1]];
      distance[b] = segment_distance(centroid, a, c, &t);
      nearest[b] = a + t * (c - a);
      closest = std::min(closest, distance[b]);
    }
    // "Out of the tube" is the gradient of a smooth minimum of the distances
    // to the bones: away from the nearest bone along a tube, and out of the
    // crotch where two bones are about equally near (where the nearest bone
    // alone would flip between them).
    double scale = std::max(0.3 * closest, 1e-12);
    Eigen::Vector3d outward = Eigen::Vector3d::Zero();
    for (size_t b = 0; b < skeleton.edges.size(); ++b) {
      if (distance[b] > closest + 8 * scale || distance[b] <= 0) continue;
      outward += std::exp(-(distance[b] - closest) / scale) * (centroid - nearest[b]) / distance[b];
    }
    if (normal.dot(outward) < 0) inward.push_back(f.idx());
  }
  return inward;
}

}  // namespace mcquad
