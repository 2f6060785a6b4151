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

void CloseTrianglePairs::update(const MeshTriangles& triangles) {
  const size_t vertices = triangles.positions.size();
  if (reference_.positions.size() != vertices) return build(triangles);
  double extent = 0;
  for (const Eigen::Vector3d& p : triangles.positions) extent = std::max(extent, p.cwiseAbs().maxCoeff());
  // Two boxes that overlap now were within the two triangles' largest moves
  // from their references, twice the largest of one vertex. The list's
  // boxes are floats and so is its gap test: allow for a few roundings at
  // the coordinates' magnitude.
  const double slack = 8 * FLT_EPSILON * (extent + gap_);
  std::vector<uint32_t> gone;
  for (size_t v = 0; v < vertices; ++v)
    if (2 * (triangles.positions[v] - reference_.positions[v]).cwiseAbs().maxCoeff() + slack > gap_)
      gone.push_back(uint32_t(v));
  if (gone.empty()) return;
  std::vector<char> stale(triangles.size(), 0);
  size_t stale_count = 0;
  for (uint32_t v : gone) {
    reference_.positions[v] = triangles.positions[v];
    for (uint32_t j = vertex_triangle_offsets_[v]; j < vertex_triangle_offsets_[v + 1]; ++j)
      stale_count += !stale[vertex_triangles_[j]], stale[vertex_triangles_[j]] = 1;
  }
  if (stale_count * kMostStaleShare > triangles.size()) return build(triangles);
  refresh(stale);
}

void CloseTrianglePairs::build(const MeshTriangles& triangles) {
  reference_ = triangles;
  const size_t vertices = triangles.positions.size();
  vertex_triangle_offsets_.assign(vertices + 1, 0);
  for (const auto& corners : triangles.corners)
    for (int v : corners) ++vertex_triangle_offsets_[size_t(v) + 1];
  for (size_t v = 0; v < vertices; ++v) vertex_triangle_offsets_[v + 1] += vertex_triangle_offsets_[v];
  vertex_triangles_.resize(vertex_triangle_offsets_.back());
  std::vector<uint32_t> next(vertex_triangle_offsets_.begin(), vertex_triangle_offsets_.end() - 1);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int v : triangles.corners[t]) vertex_triangles_[next[size_t(v)]++] = uint32_t(t);
  partners_.assign(triangles.size(), {});
  add_pairs(nullptr);
  ++builds_;
}

void CloseTrianglePairs::refresh(const std::vector<char>& stale) {
  for (size_t t = 0; t < partners_.size(); ++t) {
    if (!stale[t]) continue;
    for (uint32_t p : partners_[t]) {
      if (stale[p]) continue;
      auto& theirs = partners_[p];
      theirs.erase(std::find(theirs.begin(), theirs.end(), uint32_t(t)));
    }
    partners_[t].clear();
  }
  add_pairs(&stale);
  ++refreshes_;
}

void CloseTrianglePairs::add_pairs(const std::vector<char>* wanted) {
  TriangleTree tree(reference_);
  std::vector<std::vector<std::pair<uint32_t, uint32_t>>> found(static_cast<size_t>(omp_get_max_threads()));
  tree.for_each_overlapping_pair(
      wanted,
      [&](size_t a, size_t b, int thread) {
        if (reference_.face[a] == reference_.face[b] || triangles_share_a_vertex(reference_, a, b)) return;
        found[size_t(thread)].emplace_back(uint32_t(a), uint32_t(b));
      },
      8192, float(gap_));
  for (const auto& some : found)
    for (const auto& [a, b] : some) {
      partners_[a].push_back(b);
      partners_[b].push_back(a);
    }
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
    for (uint32_t p : partners_[t])
      if ((only_faces || p > t) && triangle_pair_intersects(triangles, t, p))
        found.add(triangles, t, p, omp_get_thread_num());
  }
  return found.sorted();
}

}  // namespace mcquad
