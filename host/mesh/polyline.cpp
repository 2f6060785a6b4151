#include "mesh/polyline.h"

#include <algorithm>

namespace mcquad {

std::pair<Eigen::Vector3d, Eigen::Vector3d> point_at(const std::vector<Eigen::Vector3d>& line, double s) {
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    double span = (line[i + 1] - line[i]).norm();
    if (s <= span || i + 2 == line.size()) {
      double t = span > 0 ? std::clamp(s / span, 0.0, 1.0) : 0.0;
      return {line[i] + t * (line[i + 1] - line[i]), (line[i + 1] - line[i]).normalized()};
    }
    s -= span;
  }
  return {line.back(), Eigen::Vector3d::UnitZ()};
}

double polyline_length(const std::vector<Eigen::Vector3d>& line) {
  double length = 0;
  for (size_t i = 0; i + 1 < line.size(); ++i) length += (line[i + 1] - line[i]).norm();
  return length;
}

std::vector<Eigen::Vector3d> sub_polyline(const std::vector<Eigen::Vector3d>& line, double s0, double s1) {
  std::vector<Eigen::Vector3d> out{point_at(line, s0).first};
  double s = 0;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    s += (line[i + 1] - line[i]).norm();
    if (s > s0 && s < s1) out.push_back(line[i + 1]);
  }
  out.push_back(point_at(line, s1).first);
  return out;
}

}  // namespace mcquad
