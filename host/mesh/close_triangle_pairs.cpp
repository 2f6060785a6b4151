#include "mesh/close_triangle_pairs.h"

#include <omp.h>

#include <algorithm>
#include <cfloat>

#include "mesh/triangle_tree.h"

namespace mcquad {
namespace {

//! Whether the list's triangles may be refreshed one by one: beyond this
//! share of the triangles gone stale, building the whole list costs less
//! (one in 8, 4 and 2 measured on the octopus's finer fit: docs/PERFORMANCE.md).
constexpr size_t kMostStaleShare = 4;  // one in 4

}  // namespace

double CloseTrianglePairs::half_mean_edge(const MeshTriangles& triangles) {
  double total = 0;
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) total += (triangles.corner(t, k) - triangles.corner(t, (k + 1) % 3)).norm();
  return triangles.size() > 0 ? 0.5 * total / double(3 * triangles.size()) : 0.0;
}

std::vector<uint32_t> CloseTrianglePairs::flat_pairs() const {
  std::vector<uint32_t> pairs;
  for (size_t t = 0; t < partners_.size(); ++t)
    for (auto p = std::upper_bound(partners_[t].begin(), partners_[t].end(), uint32_t(t)); p != partners_[t].end(); ++p)
      pairs.insert(pairs.end(), {uint32_t(t), *p});
  return pairs;
}

std::vector<float> CloseTrianglePairs::reference_floats() const {
  std::vector<float> out;
  if (!reference_) return out;
  out.reserve(3 * reference_->triangles.positions.size());
  for (const Eigen::Vector3d& p : reference_->triangles.positions)
    out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z())});
  return out;
}

double CloseTrianglePairs::move_limit() const {
  double extent = 0;
  if (reference_)
    for (const Eigen::Vector3d& p : reference_->triangles.positions) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  // While no vertex is past the limit, none is more than gap / 2 from its
  // reference, so the positions' extent is at most extent + gap / 2; the
  // allowance is taken twice, so that no rounding of the comparison itself
  // can put the device's test on the other side of update()'s.
  return gap_ - 2 * rounding_slack(extent + 0.5 * gap_);
}

double CloseTrianglePairs::rounding_slack(double extent) const { return 8 * FLT_EPSILON * (extent + gap_); }

void CloseTrianglePairs::update(const MeshTriangles& triangles) {
  const size_t vertices = triangles.positions.size();
  if (!reference_ || reference_->triangles.positions.size() != vertices || partners_.size() != triangles.size())
    return build(triangles);
  std::vector<Eigen::Vector3d>& reference = reference_->triangles.positions;
  double extent = 0;
  for (const Eigen::Vector3d& p : triangles.positions) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  // Two boxes that overlap now were within the two triangles' largest moves
  // from their references, twice the largest of one vertex. The list's
  // boxes are floats and so is its gap test: allow for a few roundings at
  // the coordinates' magnitude.
  const double slack = rounding_slack(extent);
  std::vector<double> moved(vertices);
  bool any = false;
  for (size_t v = 0; v < vertices; ++v) {
    moved[v] = 2 * (triangles.positions[v] - reference[v]).cwiseAbs().maxCoeff() + slack;
    any |= moved[v] > gap_;
  }
  if (!any) return;
  // Those gone too far, and with them those half way there: where the whole
  // mesh drifts (the knot's steps), the next call would find the next few
  // gone, and a refresh each step cost more than a rebuild now and then.
  std::vector<char> gone(vertices, 0);
  for (size_t v = 0; v < vertices; ++v) gone[v] = moved[v] > 0.5 * gap_;
  std::vector<char> stale(triangles.size(), 0);
  size_t stale_count = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& c = triangles.corners[t];
    stale[t] = gone[size_t(c[0])] || gone[size_t(c[1])] || gone[size_t(c[2])];
    stale_count += size_t(stale[t]);
  }
  if (stale_count * kMostStaleShare > triangles.size()) return build(triangles);  // every vertex starts afresh
  for (size_t v = 0; v < vertices; ++v)
    if (gone[v]) reference[v] = triangles.positions[v];
  refresh(stale);
}

void CloseTrianglePairs::build(const MeshTriangles& triangles) {
  // The old list and tree go before the new ones are made.
  std::vector<std::vector<uint32_t>>().swap(partners_);
  partners_.resize(triangles.size());
  reference_.reset();
  reference_ = std::make_unique<ReferenceTree>(triangles);
  const MeshTriangles& at_reference = reference_->triangles;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(static_cast<size_t>(omp_get_max_threads()));
  reference_->tree.for_each_overlapping_pair(
      nullptr,
      [&](size_t a, size_t b, int thread) {
        if (at_reference.face[a] == at_reference.face[b] || triangles_share_a_vertex(at_reference, a, b)) return;
        found[size_t(thread)].emplace_back(uint32_t(a), uint32_t(b));
      },
      8192, float(gap_));
  add_pairs(found);
  ++builds_;
}

void CloseTrianglePairs::refresh(const std::vector<char>& stale) {
  // The pairs of stale triangles go; those of fresh ones stay. Then the
  // stale triangles' pairs are looked for at the new references, each
  // stale triangle's box against the refitted tree: a pair of two stale
  // triangles from its lower one.
  std::vector<uint32_t> stale_triangles;
  for (size_t t = 0; t < partners_.size(); ++t) {
    if (!stale[t]) continue;
    stale_triangles.push_back(uint32_t(t));
    for (uint32_t p : partners_[t]) {
      if (stale[p]) continue;
      auto& theirs = partners_[p];
      theirs.erase(std::lower_bound(theirs.begin(), theirs.end(), uint32_t(t)));
    }
    partners_[t].clear();
  }
  reference_->tree.refit(stale);
  const MeshTriangles& at_reference = reference_->triangles;
  const TriangleTree& tree = reference_->tree;
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(static_cast<size_t>(omp_get_max_threads()));
  const long count = long(stale_triangles.size());
#pragma omp parallel for schedule(dynamic, 64) if (count > 1024)
  for (long i = 0; i < count; ++i) {
    const uint32_t a = stale_triangles[size_t(i)];
    auto& mine = found[size_t(omp_get_thread_num())];
    tree.for_each_within_gap(tree.box(a), float(gap_), [&](size_t b) {
      if ((stale[b] && b <= a) || at_reference.face[a] == at_reference.face[b] ||
          triangles_share_a_vertex(at_reference, a, b))
        return;
      mine.emplace_back(std::min(a, uint32_t(b)), std::max(a, uint32_t(b)));
    });
  }
  add_pairs(found);
  ++refreshes_;
}

void CloseTrianglePairs::add_pairs(const std::vector<std::vector<std::pair<uint32_t, uint32_t>>>& found) {
  // Counted first, so that each list grows once. Each list sorted, so that
  // the whole test reads each pair once, from its lower triangle's list,
  // past its own index.
  std::vector<uint32_t> added(partners_.size(), 0);
  for (const auto& some : found)
    for (const auto& [a, b] : some) ++added[a], ++added[b];
  for (size_t t = 0; t < partners_.size(); ++t)
    if (added[t] > 0) partners_[t].reserve(partners_[t].size() + added[t]);
  for (const auto& some : found)
    for (const auto& [a, b] : some) {
      partners_[a].push_back(b);
      partners_[b].push_back(a);
    }
  const long count = long(partners_.size());
#pragma omp parallel for schedule(dynamic, 1024) if (count > 8192)
  for (long t = 0; t < count; ++t)
    if (added[size_t(t)] > 0) std::sort(partners_[size_t(t)].begin(), partners_[size_t(t)].end());
}

std::vector<std::pair<int, int>> CloseTrianglePairs::intersecting_face_pairs(const MeshTriangles& triangles,
                                                                             const std::vector<char>* only_faces) {
  update(triangles);
  // Each listed pair once, from its lower triangle; with `only_faces`, the
  // pairs of the wanted faces' triangles (a pair of two wanted triangles is
  // tested twice; sorted() keeps it once).
  std::vector<uint32_t> tested;
  for (size_t t = 0; t < triangles.size(); ++t)
    if (!only_faces || (*only_faces)[size_t(triangles.face[t])]) tested.push_back(uint32_t(t));
  FacePairsFound found;
  const long count = long(tested.size());
#pragma omp parallel for schedule(dynamic, 256) if (count > 8192)
  for (long i = 0; i < count; ++i) {
    const uint32_t t = tested[size_t(i)];
    const auto& mine = partners_[t];
    for (auto p = only_faces ? mine.begin() : std::upper_bound(mine.begin(), mine.end(), t); p != mine.end(); ++p)
      if (triangle_pair_intersects(triangles, t, *p)) found.add(triangles, t, *p, omp_get_thread_num());
  }
  return found.sorted();
}

}  // namespace mcquad
