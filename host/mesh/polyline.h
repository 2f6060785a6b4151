#pragma once

#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace mcquad {

//! A point at arc length s along a polyline, with the unit tangent there
//! (clamped to the ends).
std::pair<Eigen::Vector3d, Eigen::Vector3d> point_at(const std::vector<Eigen::Vector3d>& line, double s);

double polyline_length(const std::vector<Eigen::Vector3d>& line);

//! The part of a polyline between arc lengths s0 and s1.
std::vector<Eigen::Vector3d> sub_polyline(const std::vector<Eigen::Vector3d>& line, double s0, double s1);

}  // namespace mcquad
