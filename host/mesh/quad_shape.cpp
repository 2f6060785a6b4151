#include "mesh/quad_shape.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/shared_math.h"

namespace mcquad {
namespace {

//! The value at fraction q of the sorted list (q = 0: the least).
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  size_t k = std::min(values.size() - 1, size_t(q * double(values.size())));
  std::nth_element(values.begin(), values.begin() + long(k), values.end());
  return values[k];
}

}  // namespace

double scaled_jacobian(const Eigen::Vector3d* c) {
  // The guard's measure, shared with the device (kernels/shared/mcq_guard.h).
  const device::mcq_d3 corners[4] = {to_device(c[0]), to_device(c[1]), to_device(c[2]), to_device(c[3])};
  return device::mcq_guard_scaled_jacobian(corners);
}

QuadShape measure_quad_shape(const QuadMesh& mesh) {
  QuadShape shape;
  std::vector<double> jacobians, ratios;
  double angle_min = 180, angle_max = 0;
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> c = face_corners(mesh, f);
    if (c.size() != 4) continue;
    double jacobian = scaled_jacobian(c.data()), shortest = INFINITY, longest = 0;
    for (size_t k = 0; k < 4; ++k) {
      Eigen::Vector3d to_next = c[(k + 1) % 4] - c[k], to_previous = c[(k + 3) % 4] - c[k];
      double angle = std::atan2(to_next.cross(to_previous).norm(), to_next.dot(to_previous)) * 180 / M_PI;
      angle_min = std::min(angle_min, angle);
      angle_max = std::max(angle_max, angle);
      shortest = std::min(shortest, to_next.norm());
      longest = std::max(longest, to_next.norm());
    }
    jacobians.push_back(jacobian);
    ratios.push_back(shortest > 0 ? longest / shortest : INFINITY);
  }
  if (jacobians.empty()) return shape;
  shape.min_scaled_jacobian = *std::min_element(jacobians.begin(), jacobians.end());
  shape.p5_scaled_jacobian = quantile(jacobians, 0.05);
  double sum = 0;
  for (double j : jacobians) sum += j;
  shape.mean_scaled_jacobian = sum / double(jacobians.size());
  shape.faces_below_half = size_t(std::count_if(jacobians.begin(), jacobians.end(), [](double j) { return j < 0.5; }));
  shape.max_edge_ratio = *std::max_element(ratios.begin(), ratios.end());
  shape.p95_edge_ratio = quantile(ratios, 0.95);
  shape.min_angle = angle_min;
  shape.max_angle = angle_max;
  return shape;
}

nlohmann::json to_json(const QuadShape& s) {
  return {{"scaled_jacobian",
           {{"min", s.min_scaled_jacobian}, {"p5", s.p5_scaled_jacobian}, {"mean", s.mean_scaled_jacobian}}},
          {"faces_scaled_jacobian_below_half", s.faces_below_half},
          {"edge_ratio", {{"max", s.max_edge_ratio}, {"p95", s.p95_edge_ratio}}},
          {"corner_angle_degrees", {{"min", s.min_angle}, {"max", s.max_angle}}}};
}

}  // namespace mcquad
