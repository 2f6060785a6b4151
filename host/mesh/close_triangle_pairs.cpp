#include "mesh/close_triangle_pairs.h"

#include <omp.h>

#include <algorithm>
#include <cfloat>

#include "mesh/triangle_tree.h"

namespace mcquad {

bool CloseTrianglePairs::moved_too_far(const MeshTriangles& triangles) const {
  if (reference_.size() != triangles.positions.size()) return true;
  double moved = 0, extent = 0;
  for (size_t v = 0; v < reference_.size(); ++v) {
    moved = std::max(moved, (triangles.positions[v] - reference_[v]).cwiseAbs().maxCoeff());
    extent = std::max(extent, triangles.positions[v].cwiseAbs().maxCoeff());
  }
  // Two boxes that overlap now were within 2 * moved of each other at the
  // reference. The list's boxes are floats and so is its gap test: allow
  // for a few roundings at the coordinates' magnitude.
  return 2 * moved + 8 * FLT_EPSILON * (extent + gap_) > gap_;
}

void CloseTrianglePairs::build(const MeshTriangles& triangles) {
  TriangleTree tree(triangles);
  std::vector<std::vector<std::pair<int, int>>> found(static_cast<size_t>(omp_get_max_threads()));
  tree.for_each_overlapping_pair(
      nullptr,
      [&](size_t a, size_t b, int thread) {
        if (triangles.face[a] == triangles.face[b] || triangles_share_a_vertex(triangles, a, b)) return;
        found[size_t(thread)].emplace_back(int(a), int(b));
      },
      8192, float(gap_));
  candidates_.clear();
  for (const auto& some : found) candidates_.insert(candidates_.end(), some.begin(), some.end());
  reference_ = triangles.positions;
  ++builds_;
}

std::vector<std::pair<int, int>> CloseTrianglePairs::intersecting_face_pairs(const MeshTriangles& triangles,
                                                                             const std::vector<char>* only_faces) {
  if (moved_too_far(triangles)) build(triangles);
  auto wanted = [&](int t) { return !only_faces || (*only_faces)[size_t(triangles.face[size_t(t)])]; };
  FacePairsFound found;
  const long count = long(candidates_.size());
#pragma omp parallel for schedule(static) if (count > 65536)
  for (long k = 0; k < count; ++k) {
    auto [a, b] = candidates_[size_t(k)];
    if ((wanted(a) || wanted(b)) && triangle_pair_intersects(triangles, size_t(a), size_t(b)))
      found.add(triangles, size_t(a), size_t(b), omp_get_thread_num());
  }
  return found.sorted();
}

}  // namespace mcquad
