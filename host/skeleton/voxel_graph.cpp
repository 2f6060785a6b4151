#include "skeleton/voxel_graph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <unordered_map>
#include <unordered_set>

#include "core/grid_cells.h"
#include "core/grid_spacing.h"

namespace mcquad {
namespace {

size_t occupied_voxels(const std::vector<Eigen::Vector3f>& points, size_t stride, const GridCells& keys) {
  std::unordered_set<uint64_t> occupied;
  occupied.reserve(points.size() / stride / 2 + 16);
  for (size_t i = 0; i < points.size(); i += stride) occupied.insert(keys.key_of(points[i]));
  return occupied.size();
}

}  // namespace

double voxel_size_for(const std::vector<Eigen::Vector3f>& points, size_t target_voxels) {
  auto [lo, hi] = box_of(points);
  double smallest = GridCells::smallest_size(lo, hi);
  size_t stride = std::max<size_t>(1, points.size() / 200000);
  double size = std::max((hi - lo).norm() / 100.0, smallest);
  // Newton-like steps on count ~ size^-2; a few reach 10 %.
  for (int step = 0; step < 8; ++step) {
    size_t count = occupied_voxels(points, stride, GridCells{lo, size});
    double ratio = double(count) / double(std::max<size_t>(1, target_voxels));
    if (std::abs(ratio - 1.0) < 0.1) break;
    size = std::max(size * std::sqrt(std::clamp(ratio, 0.05, 20.0)), smallest);
  }
  return size;
}

double sparse_spacing(const std::vector<Eigen::Vector3f>& points) { return grid_spacing_quantile(points, 0.9); }

VoxelGraph build_voxel_graph(const std::vector<Eigen::Vector3f>& points, double voxel_size) {
  VoxelGraph graph;
  auto [lo, hi] = box_of(points);
  graph.voxel_size = std::max(voxel_size, GridCells::smallest_size(lo, hi));
  GridCells keys{lo, graph.voxel_size};
  std::unordered_map<uint64_t, uint32_t> index;
  std::vector<uint64_t> voxel_keys;
  std::vector<uint32_t> counts;
  for (const auto& p : points) {
    uint64_t key = keys.key_of(p);
    auto [it, inserted] = index.try_emplace(key, uint32_t(voxel_keys.size()));
    if (inserted) {
      voxel_keys.push_back(key);
      graph.centroids.emplace_back(Eigen::Vector3d::Zero());
      counts.push_back(0);
    }
    graph.centroids[it->second] += p.cast<double>();
    ++counts[it->second];
  }
  for (size_t v = 0; v < graph.size(); ++v) graph.centroids[v] /= double(counts[v]);

  // Each unordered pair once (the 13 forward offsets), then both directions.
  std::vector<std::vector<std::pair<uint32_t, float>>> adjacent(graph.size());
  const double reach = 2.0 * graph.voxel_size;
  for (uint32_t v = 0; v < graph.size(); ++v) {
    const GridCells::Cell cell = GridCells::cell_of_key(voxel_keys[v]);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          if (dx * 9 + dy * 3 + dz <= 0) continue;  // the forward half
          const GridCells::Cell next{cell[0] + dx, cell[1] + dy, cell[2] + dz};
          if (!GridCells::exists(next)) continue;
          auto found = index.find(GridCells::key(next));
          if (found == index.end()) continue;
          double length = (graph.centroids[v] - graph.centroids[found->second]).norm();
          if (length > reach) continue;
          adjacent[v].emplace_back(found->second, float(length));
          adjacent[found->second].emplace_back(v, float(length));
        }
  }
  graph.offsets.assign(graph.size() + 1, 0);
  for (size_t v = 0; v < graph.size(); ++v) graph.offsets[v + 1] = graph.offsets[v] + uint32_t(adjacent[v].size());
  graph.neighbours.reserve(graph.offsets.back());
  graph.lengths.reserve(graph.offsets.back());
  for (auto& list : adjacent) {
    std::sort(list.begin(), list.end());
    for (auto [w, length] : list) {
      graph.neighbours.push_back(w);
      graph.lengths.push_back(length);
    }
  }
  return graph;
}

std::vector<int> voxel_components(const VoxelGraph& graph, int& count) {
  std::vector<int> label(graph.size(), -1);
  count = 0;
  std::vector<uint32_t> stack;
  for (uint32_t start = 0; start < graph.size(); ++start) {
    if (label[start] >= 0) continue;
    label[start] = count;
    stack.assign(1, start);
    while (!stack.empty()) {
      uint32_t v = stack.back();
      stack.pop_back();
      for (uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e)
        if (label[graph.neighbours[e]] < 0) {
          label[graph.neighbours[e]] = count;
          stack.push_back(graph.neighbours[e]);
        }
    }
    ++count;
  }
  return label;
}

std::vector<double> geodesic_distances(const VoxelGraph& graph, const std::vector<uint32_t>& sources) {
  std::vector<double> distance(graph.size(), std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (uint32_t s : sources) {
    distance[s] = 0;
    queue.emplace(0.0, s);
  }
  while (!queue.empty()) {
    auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;
    for (uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
      double through = d + double(graph.lengths[e]);
      uint32_t w = graph.neighbours[e];
      if (through < distance[w]) {
        distance[w] = through;
        queue.emplace(through, w);
      }
    }
  }
  return distance;
}

}  // namespace mcquad
