#pragma once

#include <Eigen/Core>
#include <sstream>
#include <string>

namespace mcquad {

//! "(x, y, z)" for messages.
inline std::string point_text(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

}  // namespace mcquad
