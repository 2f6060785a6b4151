#include "metrics/winding_number.h"

#include <cmath>
#include <vector>

namespace mcquad {

double winding_number(const QuadMesh& mesh, const Eigen::Vector3d& p) {
  // Van Oosterom-Strackee solid angle of every triangle.
  double total = 0;
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> c;
    for (auto v : mesh.fv_range(f)) c.emplace_back(point_of(mesh, v) - p);
    for (size_t k = 1; k + 1 < c.size(); ++k) {
      const Eigen::Vector3d &a = c[0], &b = c[k], &d = c[k + 1];
      double la = a.norm(), lb = b.norm(), ld = d.norm();
      double numerator = a.dot(b.cross(d));
      double denominator = la * lb * ld + a.dot(b) * ld + b.dot(d) * la + d.dot(a) * lb;
      total += 2.0 * std::atan2(numerator, denominator);
    }
  }
  return total / (4.0 * M_PI);
}

}  // namespace mcquad
