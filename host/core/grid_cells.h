#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace mcquad {

//! The cells of a uniform grid of edge `size` from `origin`, each named by
//! one 64-bit key: 21 bits per axis, a million cells along a side. Points
//! outside the million are clamped into the border cells. The skeleton's
//! voxels and the exact spacing measure bin points with it.
struct GridCells {
  static constexpr int kAxisBits = 21;
  static constexpr int64_t kAxisCells = int64_t(1) << kAxisBits;
  using Cell = std::array<int64_t, 3>;

  Eigen::Vector3d origin;
  double size;

  Cell cell_of(const Eigen::Vector3f& p) const {
    Eigen::Vector3d c = ((p.cast<double>() - origin) / size).array().floor();
    return {std::clamp<int64_t>(int64_t(c.x()), 0, kAxisCells - 1),
            std::clamp<int64_t>(int64_t(c.y()), 0, kAxisCells - 1),
            std::clamp<int64_t>(int64_t(c.z()), 0, kAxisCells - 1)};
  }
  uint64_t key_of(const Eigen::Vector3f& p) const { return key(cell_of(p)); }

  static bool exists(const Cell& c) {
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < kAxisCells && c[1] < kAxisCells && c[2] < kAxisCells;
  }
  static uint64_t key(const Cell& c) {
    return (uint64_t(c[0]) << (2 * kAxisBits)) | (uint64_t(c[1]) << kAxisBits) | uint64_t(c[2]);
  }
  static Cell cell_of_key(uint64_t key) {
    return {int64_t(key >> (2 * kAxisBits)), int64_t((key >> kAxisBits) & (kAxisCells - 1)),
            int64_t(key & (kAxisCells - 1))};
  }
  //! The smallest edge whose cells still cover a box of this extent.
  static double smallest_size(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return std::max((hi - lo).maxCoeff() / double(kAxisCells - 2), 1e-300);
  }
};

//! The box of `points`, in double precision.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> box_of(const std::vector<Eigen::Vector3f>& points) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d hi = -lo;
  for (const auto& p : points) {
    lo = lo.cwiseMin(p.cast<double>());
    hi = hi.cwiseMax(p.cast<double>());
  }
  return {lo, hi};
}

}  // namespace mcquad
