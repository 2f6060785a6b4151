#include "skeleton/level_set_graph.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <set>

#include "core/union_find.h"

namespace mcquad {
namespace {

double widest_angular_gap(std::vector<double> angles) {
  if (angles.size() < 2) return 2 * M_PI;
  std::sort(angles.begin(), angles.end());
  double widest = angles.front() + 2 * M_PI - angles.back();
  for (size_t k = 1; k < angles.size(); ++k) widest = std::max(widest, angles[k] - angles[k - 1]);
  return widest;
}

}  // namespace

RingFit fit_ring(const std::vector<Eigen::Vector3d>& points) {
  RingFit fit;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : points) centroid += p;
  centroid /= double(std::max<size_t>(1, points.size()));
  fit.centre = centroid;
  auto spread_from = [&](const Eigen::Vector3d& c) {
    double sum = 0;
    for (const auto& p : points) sum += (p - c).norm();
    return sum / double(std::max<size_t>(1, points.size()));
  };
  fit.radius = spread_from(centroid);
  fit.widest_gap = 2 * M_PI;
  if (points.size() < 6) return fit;

  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - centroid) * (p - centroid).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  Eigen::Vector3d u = eigen.eigenvectors().col(2), v = eigen.eigenvectors().col(1);
  if (eigen.eigenvalues()(1) <= 1e-12 * eigen.eigenvalues()(2)) return fit;  // collinear

  // x^2 + y^2 = 2 a x + 2 b y + c, least squares in the plane of u, v.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  for (const auto& p : points) {
    double x = (p - centroid).dot(u), y = (p - centroid).dot(v);
    Eigen::Vector3d row(2 * x, 2 * y, 1.0);
    normal += row * row.transpose();
    right += row * (x * x + y * y);
  }
  Eigen::Vector3d solution = normal.ldlt().solve(right);
  Eigen::Vector3d centre = centroid + solution(0) * u + solution(1) * v;
  // A circle centre far outside the piece is an arc's (a sheet's, a crease's):
  // keep the centroid for the position, but report the arc's gap.
  std::vector<double> angles;
  angles.reserve(points.size());
  for (const auto& p : points) angles.push_back(std::atan2((p - centre).dot(v), (p - centre).dot(u)));
  fit.widest_gap = widest_angular_gap(std::move(angles));
  if (!centre.allFinite() || (centre - centroid).norm() > fit.radius) return fit;
  fit.centre = centre;
  fit.radius = spread_from(centre);
  return fit;
}

LevelSetGraph build_level_set_graph(const VoxelGraph& graph, const std::vector<double>& distance, double band_width) {
  auto band_of = [&](uint32_t v) { return int(std::floor(distance[v] / band_width)); };
  auto usable = [&](uint32_t v) { return std::isfinite(distance[v]) && distance[v] >= 0; };
  UnionFind pieces(graph.size());
  for (uint32_t v = 0; v < graph.size(); ++v) {
    if (!usable(v)) continue;
    for (uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
      uint32_t w = graph.neighbours[e];
      if (w > v && usable(w) && band_of(w) == band_of(v)) pieces.join(v, w);
    }
  }
  LevelSetGraph result;
  std::vector<int> node_of(graph.size(), -1);
  for (uint32_t v = 0; v < graph.size(); ++v) {
    if (!usable(v)) continue;
    size_t leader = pieces.find(v);
    if (node_of[leader] < 0) {
      node_of[leader] = int(result.nodes.size());
      result.nodes.push_back(LevelSetNode{band_of(v), {}, Eigen::Vector3d::Zero(), 0, 0});
    }
    node_of[v] = node_of[leader];
    result.nodes[size_t(node_of[v])].voxels.push_back(v);
  }
  std::set<std::array<int, 2>> edges;
  for (uint32_t v = 0; v < graph.size(); ++v) {
    if (node_of[v] < 0) continue;
    for (uint32_t e = graph.offsets[v]; e < graph.offsets[v + 1]; ++e) {
      int a = node_of[v], b = node_of[graph.neighbours[e]];
      if (b >= 0 && a != b) edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  result.edges.assign(edges.begin(), edges.end());
  std::vector<Eigen::Vector3d> points;
  for (auto& node : result.nodes) {
    points.clear();
    for (uint32_t v : node.voxels) points.push_back(graph.centroids[v]);
    RingFit ring = fit_ring(points);
    node.centre = ring.centre;
    node.radius = ring.radius;
    node.widest_gap = ring.widest_gap;
  }
  return result;
}

}  // namespace mcquad
