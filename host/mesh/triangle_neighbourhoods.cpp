#include "mesh/triangle_neighbourhoods.h"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "core/quantile.h"

namespace mcquad {

TriangleNeighbourhoods::TriangleNeighbourhoods(const TriangleTree& tree, size_t queries) : tree_(tree) {
  const size_t n = tree.size();
  if (double(queries) < kLeastQueriesPerTriangle * double(n)) return;
  // Half a triangle's box diagonal: most points of a cloud the mesh fits lie
  // nearer than a quarter of it to the previous point's triangle. Capped at
  // the 95th percentile, so that a few large triangles do not widen the
  // search for all.
  reach_.resize(n);
  for (size_t t = 0; t < n; ++t) reach_[t] = 0.5 * double(tree.box(t).diagonal().norm());
  const double cap = n > 0 ? quantile_of(reach_, 0.95) : 0.0;
  for (double& reach : reach_) reach = std::min(reach, cap);
  // Box gaps are measured in floats; a pair is kept when it is within reach
  // by a margin of their rounding.
  auto rounding = [&](size_t t) {
    return 1e-6 * double(std::max(tree.box(t).max().cwiseAbs().maxCoeff(), tree.box(t).min().cwiseAbs().maxCoeff()));
  };
  const size_t threads = size_t(omp_get_max_threads());
  std::vector<std::vector<std::pair<int, Neighbour>>> found(threads);
  tree.for_each_overlapping_pair(
      nullptr,
      [&](size_t a, size_t b, int thread) {
        double gap = std::sqrt(double(tree.box(a).squaredExteriorDistance(tree.box(b))));
        double slack = gap * 1e-6 + rounding(a) + rounding(b);
        if (gap <= reach_[a] + slack) found[size_t(thread)].push_back({int(a), {gap, int(b)}});
        if (gap <= reach_[b] + slack) found[size_t(thread)].push_back({int(b), {gap, int(a)}});
      },
      8192, float(cap * (1 + 1e-5)));
  offsets_.assign(n + 1, 0);
  for (const auto& pairs : found)
    for (const auto& pair : pairs) ++offsets_[size_t(pair.first) + 1];
  for (size_t t = 0; t < n; ++t) offsets_[t + 1] += offsets_[t];
  neighbours_.resize(offsets_[n]);
  std::vector<size_t> next(offsets_.begin(), offsets_.end() - 1);
  for (const auto& pairs : found)
    for (const auto& pair : pairs) neighbours_[next[size_t(pair.first)]++] = pair.second;
      // Nearest box first, ties by index: the same lists whatever the threads did.
#pragma omp parallel for schedule(dynamic, 256)
  for (long t = 0; t < long(n); ++t)
    std::sort(neighbours_.begin() + long(offsets_[size_t(t)]), neighbours_.begin() + long(offsets_[size_t(t) + 1]),
              [](const Neighbour& x, const Neighbour& y) {
                return x.gap < y.gap || (x.gap == y.gap && x.triangle < y.triangle);
              });
}

std::pair<double, long> TriangleNeighbourhoods::nearest(const Eigen::Vector3d& p, long hint) const {
  if (offsets_.empty() || hint < 0 || size_t(hint) >= tree_.size()) return tree_.nearest(p, hint);
  const double to_hint = tree_.triangle_distance(p, size_t(hint));
  if (!(2 * to_hint < reach_[size_t(hint)])) return tree_.nearest(p, hint);
  double best = to_hint;
  long best_triangle = hint;
  const Eigen::Vector3f q = p.cast<float>();
  const double slack = TriangleTree::rounding_slack(q);
  for (size_t k = offsets_[size_t(hint)]; k < offsets_[size_t(hint) + 1]; ++k) {
    const Neighbour& u = neighbours_[k];
    // A triangle nearer to p than `best` lies within to_hint + best of the
    // hint; the rest of the list lies farther.
    if (u.gap * (1 - 1e-6) - 2 * slack > to_hint + best) break;
    if (TriangleTree::beyond(TriangleTree::box_distance2(tree_.box(size_t(u.triangle)), q), best, slack)) continue;
    double d = tree_.triangle_distance(p, size_t(u.triangle));
    if (TriangleTree::nearer(d, u.triangle, best, best_triangle)) best = d, best_triangle = u.triangle;
  }
  return {best, best_triangle};
}

}  // namespace mcquad
