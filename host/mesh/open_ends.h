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

//! How far beyond `end`, along `outward`, the cloud's tube goes on: the last
//! distance t (up to 4 radii, in steps of `step`) at which cloud points lie
//! within `step` of the cross-section at t, within 1.25 radii of the axis,
//! in three of the four quarters round it (a limb beside the axis fills one
//! or two); 0 when the cloud stops at the end. One empty step is a sampling
//! gap, two end the tube.
double cloud_extent_beyond(const PointIndex<float>& index, const PointCloud& cloud, const Eigen::Vector3d& end,
                           const Eigen::Vector3d& outward, double radius, double step);

}  // namespace mcquad
