#include "core/point_cloud.h"

namespace mcquad {

std::pair<Eigen::Vector3f, Eigen::Vector3f> bounding_box(const PointCloud& cloud) {
  if (cloud.empty()) return {Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()};
  Eigen::Vector3f lo = cloud.points.front(), hi = cloud.points.front();
  for (const auto& p : cloud.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return {lo, hi};
}

}  // namespace mcquad
