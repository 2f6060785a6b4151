#include "mesh/crossing_tracker.h"

#include <algorithm>

namespace mcquad {

CrossingTracker::CrossingTracker(const QuadMesh& mesh)
    : triangles_(triangulate(mesh)), close_(CloseTrianglePairs::half_mean_edge(triangles_)) {
  // One plain search: most meshes have no crossing and stop here. The list
  // is built at the first search after a move.
  pairs_ = intersecting_face_pairs(triangles_);
}

std::vector<std::pair<int, int>> CrossingTracker::pairs(const QuadMesh& mesh) {
  std::vector<char> moved_faces(mesh.n_faces(), 0);
  size_t moved = 0;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = point_of(mesh, v);
    Eigen::Vector3d& known = triangles_.positions[size_t(v.idx())];
    if (p == known) continue;
    known = p;
    for (auto f : mesh.vf_range(v)) moved += !moved_faces[size_t(f.idx())], moved_faces[size_t(f.idx())] = 1;
  }
  if (moved == 0) return pairs_;
  if (2 * moved > mesh.n_faces()) {
    pairs_ = close_.intersecting_face_pairs(triangles_);
    return pairs_;
  }
  // Among faces none of whose corners moved, the pairs are as they were.
  std::vector<std::pair<int, int>> now = close_.intersecting_face_pairs(triangles_, &moved_faces);
  for (const auto& [a, b] : pairs_)
    if (!moved_faces[size_t(a)] && !moved_faces[size_t(b)]) now.emplace_back(a, b);
  std::sort(now.begin(), now.end());
  now.erase(std::unique(now.begin(), now.end()), now.end());
  pairs_.swap(now);
  return pairs_;
}

}  // namespace mcquad
