#include "mesh/frames.h"

#include <cmath>

namespace mcquad {

SweepPath resample_polyline(const std::vector<Eigen::Vector3d>& polyline, int segments, bool closed) {
  std::vector<Eigen::Vector3d> line = polyline;
  if (closed) line.push_back(polyline.front());
  std::vector<double> cumulative(line.size(), 0.0);
  for (size_t i = 1; i < line.size(); ++i) cumulative[i] = cumulative[i - 1] + (line[i] - line[i - 1]).norm();
  double total = cumulative.back();
  SweepPath path;
  size_t piece = 0;
  for (int k = 0; k <= segments; ++k) {
    double s = total * k / segments;
    while (piece + 2 < line.size() && cumulative[piece + 1] < s) ++piece;
    double span = cumulative[piece + 1] - cumulative[piece];
    double t = span > 0 ? std::clamp((s - cumulative[piece]) / span, 0.0, 1.0) : 0.0;
    path.points.emplace_back(line[piece] + t * (line[piece + 1] - line[piece]));
    path.arc_length.push_back(s);
  }
  size_t n = path.points.size();
  for (size_t k = 0; k < n; ++k) {
    Eigen::Vector3d previous, next;
    if (closed) {
      previous = path.points[k == 0 ? n - 2 : k - 1];
      next = path.points[k == n - 1 ? 1 : k + 1];
    } else {
      previous = path.points[k == 0 ? 0 : k - 1];
      next = path.points[k == n - 1 ? n - 1 : k + 1];
    }
    path.tangents.push_back((next - previous).normalized());
  }
  return path;
}

std::vector<Eigen::Vector3d> hermite_curve(const Eigen::Vector3d& a, const Eigen::Vector3d& ta,
                                           const Eigen::Vector3d& b, const Eigen::Vector3d& tb, int samples,
                                           double weight_a, double weight_b) {
  double chord = (b - a).norm();
  std::vector<Eigen::Vector3d> curve;
  for (int k = 0; k <= samples; ++k) {
    double t = double(k) / samples, t2 = t * t, t3 = t2 * t;
    curve.emplace_back((2 * t3 - 3 * t2 + 1) * a + (t3 - 2 * t2 + t) * weight_a * chord * ta + (-2 * t3 + 3 * t2) * b +
                       (t3 - t2) * weight_b * chord * tb);
  }
  return curve;
}

Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  Eigen::Vector3d axis = std::abs(n.x()) < 0.6 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(axis).normalized();
}

std::vector<Eigen::Vector3d> rotation_minimizing_frames(const SweepPath& path, const Eigen::Vector3d& initial) {
  std::vector<Eigen::Vector3d> u(path.points.size());
  Eigen::Vector3d t0 = path.tangents[0];
  u[0] = (initial - initial.dot(t0) * t0).normalized();
  for (size_t i = 0; i + 1 < path.points.size(); ++i) {
    Eigen::Vector3d v1 = path.points[i + 1] - path.points[i];
    double c1 = v1.squaredNorm();
    if (c1 < 1e-30) {
      u[i + 1] = u[i];
      continue;
    }
    Eigen::Vector3d r_l = u[i] - (2.0 / c1) * v1.dot(u[i]) * v1;
    Eigen::Vector3d t_l = path.tangents[i] - (2.0 / c1) * v1.dot(path.tangents[i]) * v1;
    Eigen::Vector3d v2 = path.tangents[i + 1] - t_l;
    double c2 = v2.squaredNorm();
    Eigen::Vector3d next = c2 < 1e-30 ? r_l : Eigen::Vector3d(r_l - (2.0 / c2) * v2.dot(r_l) * v2);
    const Eigen::Vector3d& t = path.tangents[i + 1];
    u[i + 1] = (next - next.dot(t) * t).normalized();
  }
  return u;
}

double signed_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& axis) {
  Eigen::Vector3d pa = a - a.dot(axis) * axis, pb = b - b.dot(axis) * axis;
  return std::atan2(axis.dot(pa.cross(pb)), pa.dot(pb));
}

}  // namespace mcquad
