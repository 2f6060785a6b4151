#include "evolution/uncovered_reach.h"

#include <algorithm>

#include "core/point_index.h"
#include "evolution/evolve.h"
#include "mesh/crossing_guard.h"
#include "mesh/face_intersections.h"
#include "mesh/triangle_tree.h"

namespace mcquad {
namespace {

//! The fewest sampled points that must pull a vertex for it to move: a
//! stray outlier or two does not.
constexpr int kLeastPullingPoints = 4;

//! A point pulls only with at least kLeastNeighbours others of the sample
//! within kNeighbourhood median spacings of it: a surface, however sparse
//! (a tenfold fall in density leaves about ten there), not an outlier. The
//! T with 1 % outliers, its scatter pulling, had its mesh -> true surface
//! mean go from 0.13 to 10.9 % of r.
constexpr double kNeighbourhood = 6.0;
constexpr size_t kLeastNeighbours = 4;

//! Those of `points` (indices into the cloud) that lie on a surface of the
//! sample `index` holds (kLeastNeighbours within kNeighbourhood spacings).
std::vector<size_t> on_a_surface(const std::vector<size_t>& points, const PointCloud& cloud,
                                 const PointIndex<float>& index) {
  const float reach = float(kNeighbourhood * index.median_spacing());
  std::vector<size_t> kept;
  for (size_t i : points)
    if (index.within(cloud.points[i], reach).size() > kLeastNeighbours) kept.push_back(i);  // itself among them
  return kept;
}

//! The pulls on every vertex, summed.
struct Pulls {
  std::vector<Eigen::Vector3d> sum;  //!< weighted pulls
  std::vector<double> weight;        //!< their weights
  std::vector<int> count;            //!< pulling points

  explicit Pulls(size_t vertices) : sum(vertices, Eigen::Vector3d::Zero()), weight(vertices, 0.0), count(vertices, 0) {}

  //! Point p, nearest to q on `triangle`, pulls its corners.
  void add(const MeshTriangles& triangles, size_t triangle, const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    const Eigen::Vector3d &a = triangles.corner(triangle, 0), &b = triangles.corner(triangle, 1),
                          &c = triangles.corner(triangle, 2);
    const double area = (b - a).cross(c - a).norm();
    if (area <= 0) return;
    // Barycentric weights of q: the corners nearest it pull hardest.
    const double wa = (b - q).cross(c - q).norm() / area, wb = (c - q).cross(a - q).norm() / area;
    const double weights[3] = {wa, wb, std::max(0.0, 1.0 - wa - wb)};
    for (int k = 0; k < 3; ++k) {
      const size_t v = size_t(triangles.corners[triangle][size_t(k)]);
      sum[v] += weights[k] * (p - q);
      weight[v] += weights[k];
      ++count[v];
    }
  }
};

//! The pulls of those of `candidates` (indices into the cloud) farther than
//! `distance` from the mesh; their indices go to `uncovered`, in the order
//! of `candidates`.
Pulls pulls_toward_uncovered(const QuadMesh& mesh, const PointCloud& cloud, const std::vector<size_t>& candidates,
                             double distance, std::vector<size_t>& uncovered) {
  const MeshTriangles triangles = triangulate(mesh);
  const TriangleTree tree(triangles);
  const long count = long(candidates.size());
  std::vector<long> nearest(candidates.size(), -1);  // -1: covered
  std::vector<Eigen::Vector3d> foot(candidates.size());
#pragma omp parallel
  {
    long hint = -1;  // the cloud is sorted spatially: the last answer is near
#pragma omp for schedule(static)
    for (long i = 0; i < count; ++i) {
      const Eigen::Vector3d p = cloud.points[candidates[size_t(i)]].cast<double>();
      const auto [gap, triangle] = tree.nearest(p, hint);  // the same triangle whatever the hint
      hint = triangle;
      if (triangle < 0 || gap <= distance) continue;
      const size_t t = size_t(triangle);
      nearest[size_t(i)] = triangle;
      foot[size_t(i)] =
          closest_point_on_triangle(p, triangles.corner(t, 0), triangles.corner(t, 1), triangles.corner(t, 2));
    }
  }
  // Summed in one thread, in the candidates' order: the same sums, to the
  // last bit, whatever the thread count.
  Pulls pulls(triangles.positions.size());
  uncovered.clear();
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (nearest[i] < 0) continue;
    uncovered.push_back(candidates[i]);
    pulls.add(triangles, size_t(nearest[i]), cloud.points[candidates[i]].cast<double>(), foot[i]);
  }
  return pulls;
}

}  // namespace

UncoveredReach pull_toward_uncovered_cloud(QuadMesh& mesh, const MeshArrays& start, const PointCloud& cloud,
                                           double distance, double longest_step, int rounds) {
  UncoveredReach result;
  if (cloud.empty() || distance <= 0 || rounds <= 0) return result;
  CrossingGuard guard(start);
  std::vector<float> before = mesh_positions(mesh);
  // The first round looks at a sample of the whole cloud; each later one
  // only at the points still uncovered: the moves are short and toward
  // those points, and a full look each round cost more than the evolution.
  std::vector<size_t> candidates, uncovered;
  std::vector<Eigen::Vector3f> sample;
  // The same points as the fit's coverage test (covers_more) samples.
  const size_t stride = cloud_sample_stride(cloud.size(), kReachSampledPoints);
  for (size_t i = 0; i < cloud.size(); i += stride) {
    candidates.push_back(i);
    sample.push_back(cloud.points[i]);
  }
  pulls_toward_uncovered(mesh, cloud, candidates, distance, uncovered);
  result.uncovered_before = uncovered.size();
  const PointIndex<float> index(sample);
  candidates = on_a_surface(uncovered, cloud, index);
  for (int round = 0; round < rounds; ++round) {
    const Pulls pulls = pulls_toward_uncovered(mesh, cloud, candidates, distance, uncovered);
    result.uncovered_after = uncovered.size();
    std::vector<float> after = before;
    size_t pulled = 0;
    for (size_t v = 0; v < pulls.weight.size(); ++v) {
      if (pulls.count[v] < kLeastPullingPoints || pulls.weight[v] <= 0) continue;
      Eigen::Vector3d step = pulls.sum[v] / pulls.weight[v];
      if (step.norm() > longest_step) step *= longest_step / step.norm();
      for (int k = 0; k < 3; ++k) after[3 * v + size_t(k)] += float(step[k]);
      ++pulled;
    }
    if (pulled == 0) break;
    guard.apply(before, after);
    if (after == before) break;
    if (round == 0) result.vertices_moved = pulled;
    set_positions(mesh, after);
    before.swap(after);
    candidates.swap(uncovered);
    ++result.rounds;
  }
  if (result.rounds > 0) {
    pulls_toward_uncovered(mesh, cloud, candidates, distance, uncovered);
    result.uncovered_after = uncovered.size();
  }
  return result;
}

UncoveredReach reach_uncovered_cloud(EvolutionBackend& backend, const MeshArrays& start,
                                     const EvolutionParameters& parameters, const PointCloud& cloud, QuadMesh& mesh,
                                     unsigned first_iteration) {
  UncoveredReach reach = pull_toward_uncovered_cloud(mesh, start, cloud, kReachDistance * parameters.epsilon,
                                                     kReachLongestStep * parameters.epsilon, kReachRounds);
  if (reach.rounds == 0) return reach;
  settle_onto_cloud(backend, start, parameters, mesh, first_iteration, kReachSettleIterations);
  reach.settle_iterations = kReachSettleIterations;
  return reach;
}

}  // namespace mcquad
