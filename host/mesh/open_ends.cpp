#include "mesh/open_ends.h"

#include <cmath>

namespace mcquad {

bool cloud_is_open_at(const PointIndex<float>& index, const PointCloud& cloud, const Eigen::Vector3d& end,
                      const Eigen::Vector3d& outward, double radius) {
  size_t near_axis = 0, wall = 0;
  for (size_t i : index.within(end.cast<float>(), float(2.5 * radius))) {
    Eigen::Vector3d d = cloud.points[i].cast<double>() - end;
    double axial = d.dot(outward);
    double radial = (d - axial * outward).norm();
    if (axial >= -0.1 * radius && radial < 0.6 * radius) ++near_axis;
    if (axial < 0 && axial > -2.0 * radius && radial > 0.5 * radius && radial < 1.5 * radius) ++wall;
  }
  // Wall density (points per area) times the area of a cap's pole region
  // (radial distance < 0.6 r on a hemisphere: 2 pi r * 0.2 r).
  double density = wall / (2.0 * M_PI * radius * 2.0 * radius);
  double expected_on_cap = density * 0.4 * M_PI * radius * radius;
  if (expected_on_cap < 4) return false;  // too sparse to tell: keep it closed
  return near_axis < 0.25 * expected_on_cap;
}

double cloud_extent_beyond(const PointIndex<float>& index, const PointCloud& cloud, const Eigen::Vector3d& end,
                           const Eigen::Vector3d& outward, double radius, double step) {
  // Two directions across the axis, to tell a tube's cross-section (points
  // all round) from a neighbouring limb beside it (points on one side).
  const Eigen::Vector3d u = outward.unitOrthogonal(), v = outward.cross(u);
  double extent = 0;
  int empty = 0;
  for (double t = step; t <= 4.0 * radius && empty < 2; t += step) {
    const Eigen::Vector3d at = end + t * outward;
    int quadrants = 0;
    for (size_t i : index.within(at.cast<float>(), float(1.5 * radius))) {
      const Eigen::Vector3d d = cloud.points[i].cast<double>() - at;
      const double axial = d.dot(outward);
      if (std::abs(axial) > step || (d - axial * outward).norm() > 1.25 * radius) continue;
      quadrants |= 1 << ((d.dot(u) >= 0 ? 1 : 0) + (d.dot(v) >= 0 ? 2 : 0));
    }
    const bool around = __builtin_popcount(unsigned(quadrants)) >= 3;
    empty = around ? 0 : empty + 1;
    if (around) extent = t;
  }
  return extent;
}

}  // namespace mcquad
