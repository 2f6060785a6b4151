#pragma once

#include <Eigen/Geometry>
#include <vector>

namespace mcquad {

//! A sampled sweep path: positions, unit tangents and arc length.
struct SweepPath {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> tangents;
  std::vector<double> arc_length;  //!< from the start
  double length() const { return arc_length.empty() ? 0.0 : arc_length.back(); }
};

//! Resamples a polyline (open, or closed when `closed`) into `segments`
//! equal arc-length pieces, with tangents from central differences.
SweepPath resample_polyline(const std::vector<Eigen::Vector3d>& polyline, int segments, bool closed);

//! Cubic Hermite curve from a (unit tangent ta) to b (unit tangent tb),
//! sampled densely; the tangents are scaled by the chord length times
//! `weight_a` and `weight_b` (a larger weight keeps the curve straighter
//! longer at that end).
std::vector<Eigen::Vector3d> hermite_curve(const Eigen::Vector3d& a, const Eigen::Vector3d& ta,
                                           const Eigen::Vector3d& b, const Eigen::Vector3d& tb, int samples,
                                           double weight_a = 1.0, double weight_b = 1.0);

//! Rotation-minimizing frames along the path (double reflection, Wang et al.
//! 2008): u[0] = initial (made perpendicular to the first tangent), each next
//! u transported with no twist about the tangent.
std::vector<Eigen::Vector3d> rotation_minimizing_frames(const SweepPath& path, const Eigen::Vector3d& initial);

//! Any unit vector perpendicular to `n`.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n);

//! Signed angle from a to b about `axis` (both projected perpendicular to it).
double signed_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& axis);

}  // namespace mcquad
