#include "skeleton/nearest_bone.h"

#include <cmath>

#include "skeleton/bone_assignment.h"

namespace mcquad {
namespace {

//! Dense samples along every bone so a kd-tree finds the nearest bone fast;
//! `sample_bone` receives each sample's bone.
std::vector<Eigen::Vector3d> bone_samples(const SkeletonGraph& graph, std::vector<int>& sample_bone) {
  double total = 0;
  for (const auto& e : graph.edges) total += (graph.positions[e[1]] - graph.positions[e[0]]).norm();
  // Spacing fine enough to find the nearest bone's neighbourhood; the exact
  // bone is then decided against the bones sharing its nodes.
  double spacing = total / 2000.0;
  std::vector<Eigen::Vector3d> samples;
  for (size_t b = 0; b < graph.edges.size(); ++b) {
    const auto& a = graph.positions[graph.edges[b][0]];
    const auto& c = graph.positions[graph.edges[b][1]];
    int steps = std::max(2, int(std::ceil((c - a).norm() / spacing)));
    for (int k = 0; k <= steps; ++k) {
      samples.emplace_back(a + (c - a) * (double(k) / steps));
      sample_bone.push_back(int(b));
    }
  }
  return samples;
}

}  // namespace

NearestBone::NearestBone(const SkeletonGraph& graph)
    : graph_(graph), samples_(bone_samples(graph, sample_bone_)), node_bones_(graph.node_bones()), index_(samples_) {}

NearestBone::Hit NearestBone::find(const Eigen::Vector3d& p) const {
  auto distance_to = [&](int bone, double* t) {
    return segment_distance(p, graph_.positions[size_t(graph_.edges[size_t(bone)][0])],
                            graph_.positions[size_t(graph_.edges[size_t(bone)][1])], t);
  };
  Hit best;
  best.bone = sample_bone_[index_.nearest(p).first];
  best.distance = distance_to(best.bone, &best.parameter);
  int first = best.bone;
  for (int end : graph_.edges[size_t(first)])
    for (int b : node_bones_[size_t(end)]) {
      double t, d = distance_to(b, &t);
      if (d < best.distance) best = {b, t, d};
    }
  return best;
}

}  // namespace mcquad
