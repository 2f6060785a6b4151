#include "cells/skeleton_regions.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <queue>

#include "skeleton/nearest_bone.h"

namespace mcquad {
namespace {

//! Bones within `limit` of bone `bone` along the graph, itself included:
//! Dijkstra from both its ends, cut off at the limit.
std::vector<uint32_t> bones_within(const SkeletonGraph& graph, const std::vector<std::vector<int>>& node_bones,
                                   size_t bone, double limit) {
  std::vector<double> distance(graph.node_count(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int end : graph.edges[bone]) {
    distance[size_t(end)] = 0;
    queue.emplace(0.0, end);
  }
  std::vector<uint32_t> seen;
  while (!queue.empty()) {
    auto [d, node] = queue.top();
    queue.pop();
    if (d > distance[size_t(node)]) continue;
    for (int b : node_bones[size_t(node)]) {
      seen.push_back(uint32_t(b));
      const auto& e = graph.edges[size_t(b)];
      int other = e[0] == node ? e[1] : e[0];
      double next = d + (graph.positions[size_t(other)] - graph.positions[size_t(node)]).norm();
      if (next <= limit && next < distance[size_t(other)]) {
        distance[size_t(other)] = next;
        queue.emplace(next, other);
      }
    }
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  return seen;
}

//! Cells longer than this fraction of their bone's radius are split
//! (longest_cell_by_radius). 0.35 of the radius brought issue 20's shapes
//! closer still but turned more of their faces (docs/HARD_CASES.md).
constexpr float kLongestCellPerRadius = 0.5f;

}  // namespace

SkeletonRegions build_skeleton_regions(const TubeSkeleton& skeleton, const CellTree& cells, const MeshArrays& mesh,
                                       double median_radius, double window) {
  const SkeletonGraph& graph = skeleton.graph;
  NearestBone nearest(graph);
  SkeletonRegions regions;
  regions.cell_bones.resize(cells.cell_count());
#pragma omp parallel for schedule(static)
  for (long c = 0; c < long(cells.cell_count()); ++c) {
    const float* g = &cells.cell_centroids[3 * size_t(c)];
    regions.cell_bones[size_t(c)] = uint32_t(nearest.find(Eigen::Vector3d(g[0], g[1], g[2])).bone);
  }
  size_t vertices = mesh.vertex_count();
  regions.vertex_bones.resize(vertices);
  regions.vertex_scale.resize(vertices);
#pragma omp parallel for schedule(static)
  for (long v = 0; v < long(vertices); ++v) {
    const float* p = &mesh.positions[3 * size_t(v)];
    int bone = nearest.find(Eigen::Vector3d(p[0], p[1], p[2])).bone;
    regions.vertex_bones[size_t(v)] = uint32_t(bone);
    regions.vertex_scale[size_t(v)] =
        median_radius > 0 ? float(skeleton.bone_radius[size_t(bone)] / median_radius) : 1.0f;
  }
  std::vector<std::vector<int>> node_bones = graph.node_bones();
  regions.visible_offsets.push_back(0);
  for (size_t b = 0; b < graph.edges.size(); ++b) {
    std::vector<uint32_t> seen = bones_within(graph, node_bones, b, window * skeleton.bone_radius[b]);
    regions.visible_bones.insert(regions.visible_bones.end(), seen.begin(), seen.end());
    regions.visible_offsets.push_back(uint32_t(regions.visible_bones.size()));
  }
  return regions;
}

LongestLeaf longest_cell_by_radius(const TubeSkeleton& skeleton) {
  // NearestBone refers to the skeleton's graph, so the function refers to
  // the skeleton for the radii too rather than copying them.
  auto nearest = std::make_shared<const NearestBone>(skeleton.graph);
  return [nearest, &skeleton](const Eigen::Vector3f& centre) {
    return kLongestCellPerRadius * float(skeleton.bone_radius[size_t(nearest->find(centre.cast<double>()).bone)]);
  };
}

}  // namespace mcquad
