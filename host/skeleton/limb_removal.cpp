#include "skeleton/limb_removal.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "skeleton/bone_assignment.h"

namespace mcquad {

std::optional<Eigen::Vector3d> remove_limb_nearest(SkeletonData& skeleton, const Eigen::Vector3d& site) {
  const size_t n = skeleton.nodes.size();
  std::vector<std::vector<int>> neighbours(n);
  for (const auto& [a, b] : skeleton.edges) {
    neighbours[size_t(a)].push_back(b);
    neighbours[size_t(b)].push_back(a);
  }
  std::vector<int> nearest_limb;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t end = 0; end < n; ++end) {
    if (neighbours[end].size() != 1) continue;
    std::vector<int> limb{int(end)};
    int previous = -1, current = int(end);
    double distance = std::numeric_limits<double>::infinity();
    while (true) {
      int next = neighbours[size_t(current)][0] == previous ? neighbours[size_t(current)].back()
                                                            : neighbours[size_t(current)][0];
      distance = std::min(
          distance, segment_distance(site, skeleton.nodes[size_t(current)], skeleton.nodes[size_t(next)], nullptr));
      previous = current;
      current = next;
      if (neighbours[size_t(current)].size() != 2) break;
      limb.push_back(current);
    }
    if (neighbours[size_t(current)].size() < 3) continue;  // a lone chain, not a limb
    if (distance < nearest) {
      nearest = distance;
      nearest_limb = limb;
    }
  }
  if (nearest_limb.empty()) return std::nullopt;
  Eigen::Vector3d end = skeleton.nodes[size_t(nearest_limb.front())];
  std::vector<int> renumbered(n, -1);
  std::vector<bool> removed(n, false);
  for (int v : nearest_limb) removed[size_t(v)] = true;
  SkeletonData kept;
  for (size_t v = 0; v < n; ++v) {
    if (removed[v]) continue;
    renumbered[v] = int(kept.nodes.size());
    kept.nodes.push_back(skeleton.nodes[v]);
  }
  for (const auto& [a, b] : skeleton.edges)
    if (!removed[size_t(a)] && !removed[size_t(b)])
      kept.edges.push_back({renumbered[size_t(a)], renumbered[size_t(b)]});
  skeleton = std::move(kept);
  return end;
}

}  // namespace mcquad
