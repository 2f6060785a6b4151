#include "mesh/junction_inflation.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "mesh/crossing_guard.h"
#include "mesh/mesh_arrays.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/nearest_bone.h"

namespace mcquad {
namespace {

//! The inflated region's radius, in the junction's largest bone radius:
//! measured 1.8, 2.5 and 3.5 on the generated junctions (docs/DESIGN.md);
//! 2.5 reaches past the crotches of forks down to 30 degrees.
constexpr double kReachInRadii = 2.5;
//! How far a vertex may move, in its own distance to the cloud.
constexpr double kMostMoveInNearestDistance = 3.0;
//! Rounds of smoothing the offsets (measured 0, 4 and 10: 4 took the Y's and
//! the double junction's p95 down by a fifth, 10 changed little more).
constexpr int kSmoothingRounds = 4;

//! Weight of the move at distance s from the node: 1 within `inner`, then a
//! cosine down to 0 at `outer`, so the inflated region joins the tubes
//! without a step.
double fade(double s, double inner, double outer) {
  if (s <= inner) return 1.0;
  return 0.5 * (1.0 + std::cos(M_PI * (s - inner) / (outer - inner)));
}

//! The offsets a few rounds of neighbour averaging smoother: where rays from
//! the node cross a crotch, neighbouring vertices' rays meet the cloud at
//! very different distances, and moved as they are, the faces between them
//! would tilt against the surface.
std::vector<double> smoothed(const QuadMesh& mesh, std::vector<double> offset, const std::vector<bool>& in_region) {
  for (int round = 0; round < kSmoothingRounds; ++round) {
    std::vector<double> next = offset;
    for (auto v : mesh.vertices()) {
      if (!in_region[size_t(v.idx())]) continue;
      double sum = 0;
      int count = 0;
      for (auto w : mesh.vv_range(v)) {
        sum += offset[size_t(w.idx())];
        ++count;
      }
      if (count > 0) next[size_t(v.idx())] = 0.5 * offset[size_t(v.idx())] + 0.5 * sum / count;
    }
    offset.swap(next);
  }
  return offset;
}

}  // namespace

void inflate_junctions(QuadMesh& mesh, const TubeSkeleton& skeleton, const CloudProbe& probe, double fraction) {
  MeshArrays arrays = flatten_mesh(mesh);
  std::vector<float> moved = arrays.positions;
  const size_t vertex_count = moved.size() / 3;
  const SkeletonGraph& graph = skeleton.graph;
  const NearestBone bones(graph);
  auto position = [&](size_t v) { return Eigen::Vector3d(moved[3 * v], moved[3 * v + 1], moved[3 * v + 2]); };
  const std::vector<double> widest = widest_bone_radii(graph.node_count(), graph.edges, skeleton.bone_radius);
  for (size_t node = 0; node < graph.node_count(); ++node) {
    if (graph.kind(int(node)) != NodeKind::kJunction) continue;
    const double outer = kReachInRadii * widest[node], inner = 0.5 * outer;
    const Eigen::Vector3d& center = graph.positions[node];
    std::vector<double> offset(vertex_count, 0.0);
    std::vector<bool> in_region(vertex_count, false);
    for (size_t v = 0; v < vertex_count; ++v) {
      const Eigen::Vector3d p = position(v);
      const double s = (p - center).norm();
      if (s >= outer || s < 1e-9) continue;
      in_region[v] = true;
      const double target = fraction * probe.distance_along(center, (p - center) / s, 2 * outer);
      if (target <= s || target - s > kMostMoveInNearestDistance * probe.distance_to_cloud(p)) continue;
      offset[v] = fade(s, inner, outer) * (target - s);
    }
    offset = smoothed(mesh, std::move(offset), in_region);
    for (size_t v = 0; v < vertex_count; ++v) {
      if (offset[v] <= 0) continue;
      const Eigen::Vector3d p = position(v), ray = (p - center).normalized();
      // A ray grazing a crease runs on past the cloud's samples; a vertex
      // stays two sample spacings inside, as CloudProbe::keep_inside keeps it.
      double move = offset[v];
      for (int halving = 0; halving < 4 && probe.distance_to_cloud(p + move * ray) < 2 * probe.spacing(); ++halving)
        move *= 0.5;
      const Eigen::Vector3d q = p + move * ray;
      // Never toward the skeleton: a ray from this node can run along
      // another bone's tube, and a coarse ring moved along it would pass over
      // that bone and no longer wrap it.
      if (bones.find(q).distance < bones.find(p).distance) continue;
      for (int k = 0; k < 3; ++k) moved[3 * v + size_t(k)] = float(q[k]);
    }
  }
  // Nothing moved (no junction: a loop, a tube): nothing for the guard to
  // check, and building it took 14 ms on the knot's mesh.
  if (moved == arrays.positions) return;
  CrossingGuard(arrays).apply(arrays.positions, moved);
  for (auto v : mesh.vertices()) {
    const float* m = &moved[3 * size_t(v.idx())];
    mesh.set_point(v, QuadMesh::Point(m[0], m[1], m[2]));
  }
}

}  // namespace mcquad
