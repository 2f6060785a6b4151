#pragma once

#include <Eigen/Geometry>

#include "core/point_cloud.h"
#include "core/point_index.h"

namespace mcquad {

//! Whether the cloud is open at a skeleton end (a cut tube, like the leg of
//! the paper's T) rather than closed by a cap. A cap puts points near the
//! bone's axis at and beyond the end node; an open end has none there, only
//! wall points at about the radius. The count near the axis is compared with
//! what the wall's density predicts for a cap.
bool cloud_is_open_at(const PointIndex<float>& index, const PointCloud& cloud, const Eigen::Vector3d& end,
                      const Eigen::Vector3d& outward, double radius);

}  // namespace mcquad
