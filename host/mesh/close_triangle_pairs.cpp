#include "mesh/close_triangle_pairs.h"

#include <omp.h>

#include <algorithm>
#include <cfloat>

#include "mesh/triangle_tree.h"

namespace mcquad {
namespace {

//! Whether the list's triangles may be refreshed one by one: beyond this
//! share of the triangles gone stale, building the whole list costs less.
constexpr size_t kMostStaleShare = 8;  // one in 8

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
  out.reserve(3 * reference_.size());
  for (const Eigen::Vector3d& p : reference_) out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z())});
  return out;
}

double CloseTrianglePairs::move_limit() const {
  double extent = 0;
  for (const Eigen::Vector3d& p : reference_) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  // While no vertex is past the limit, none is more than gap / 2 from its
  // reference, so the positions' extent is at most extent + gap / 2; the
  // allowance is taken twice, so that no rounding of the comparison itself
  // can put the device's test on the other side of update()'s.
  return gap_ - 2 * rounding_slack(extent + 0.5 * gap_);
}

double CloseTrianglePairs::rounding_slack(double extent) const { return 8 * FLT_EPSILON * (extent + gap_); }

void CloseTrianglePairs::update(const MeshTriangles& triangles) {
  const size_t vertices = triangles.positions.size();
  if (reference_.size() != vertices || partners_.size() != triangles.size()) {
    reference_ = triangles.positions;
    return refresh(triangles, nullptr);
  }
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
    moved[v] = 2 * (triangles.positions[v] - reference_[v]).cwiseAbs().maxCoeff() + slack;
    any |= moved[v] > gap_;
  }
  if (!any) return;
  // Those gone too far, and with them those half way there: where the whole
  // mesh drifts (the knot's steps), the next call would find the next few
  // gone, and a refresh each step cost more than a rebuild now and then.
  std::vector<char> gone(vertices, 0);
  for (size_t v = 0; v < vertices; ++v)
    if (moved[v] > 0.5 * gap_) {
      gone[v] = 1;
      reference_[v] = triangles.positions[v];
    }
  std::vector<char> stale(triangles.size(), 0);
  size_t stale_count = 0;
  for (size_t t = 0; t < triangles.size(); ++t) {
    const auto& c = triangles.corners[t];
    stale[t] = gone[size_t(c[0])] || gone[size_t(c[1])] || gone[size_t(c[2])];
    stale_count += size_t(stale[t]);
  }
  if (stale_count * kMostStaleShare <= triangles.size()) return refresh(triangles, &stale);
  reference_ = triangles.positions;  // all of it again: every vertex starts afresh
  refresh(triangles, nullptr);
}

void CloseTrianglePairs::refresh(const MeshTriangles& triangles, const std::vector<char>* stale) {
  // The pairs of stale triangles go; those of fresh ones stay. Then the
  // stale triangles' pairs are looked for at the reference positions.
  if (!stale) {
    std::vector<std::vector<uint32_t>>().swap(partners_);  // the old list goes before the new one is found
    partners_.resize(triangles.size());
  } else {
    for (size_t t = 0; t < partners_.size(); ++t) {
      if (!(*stale)[t]) continue;
      for (uint32_t p : partners_[t]) {
        if ((*stale)[p]) continue;
        auto& theirs = partners_[p];
        theirs.erase(std::lower_bound(theirs.begin(), theirs.end(), uint32_t(t)));
      }
      partners_[t].clear();
    }
  }
  MeshTriangles at_reference{reference_, triangles.corners, triangles.face};
  TriangleTree tree(at_reference);
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(static_cast<size_t>(omp_get_max_threads()));
  tree.for_each_overlapping_pair(
      stale,
      [&](size_t a, size_t b, int thread) {
        if (at_reference.face[a] == at_reference.face[b] || triangles_share_a_vertex(at_reference, a, b)) return;
        found[size_t(thread)].emplace_back(uint32_t(a), uint32_t(b));
      },
      8192, float(gap_));
  // Each list sorted, so that the whole test reads each pair once, from its
  // lower triangle's list, past its own index.
  std::vector<char> touched(partners_.size(), 0);
  for (const auto& some : found)
    for (const auto& [a, b] : some) {
      partners_[a].push_back(b);
      partners_[b].push_back(a);
      touched[a] = touched[b] = 1;
    }
  const long count = long(partners_.size());
#pragma omp parallel for schedule(dynamic, 1024) if (count > 8192)
  for (long t = 0; t < count; ++t)
    if (touched[size_t(t)]) std::sort(partners_[size_t(t)].begin(), partners_[size_t(t)].end());
  ++(stale ? refreshes_ : builds_);
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
