#include "core/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/errors.h"

namespace mcquad {
namespace {

//! Spreads the low 21 bits of v to every third bit.
uint64_t spread_bits(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

}  // namespace

void sort_spatially(PointCloud& cloud) {
  if (cloud.size() < 2) return;
  // One 64-bit key a point: a 13-bit-per-axis Morton code above a 25-bit index
  // (fine enough for locality; larger clouds are sorted by the code of their
  // first 2^25 bits of index only, still correct as a permutation).
  constexpr int kIndexBits = 25;
  // Not a structured binding: the lambda below captures `lo` (C++20 allows that, clang's C++17 does not).
  const std::pair<Eigen::Vector3f, Eigen::Vector3f> box = bounding_box(cloud);
  const Eigen::Vector3f lo = box.first, hi = box.second;
  Eigen::Vector3f scale = (hi - lo).cwiseMax(1e-30f).cwiseInverse() * float((1 << 13) - 1);
  auto morton_of = [&](size_t i) {
    Eigen::Vector3f c = (cloud.points[i] - lo).cwiseProduct(scale);
    return spread_bits(uint64_t(c.x())) | spread_bits(uint64_t(c.y())) << 1 | spread_bits(uint64_t(c.z())) << 2;
  };
  std::vector<uint64_t> keys(cloud.size());
  for (size_t i = 0; i < cloud.size(); ++i)
    keys[i] = morton_of(i) << kIndexBits | (uint64_t(i) & ((uint64_t(1) << kIndexBits) - 1));
  std::sort(keys.begin(), keys.end());
  // The index bits name the point for clouds below 2^25 points; above, a
  // stable sort of indices by code does the same job.
  std::vector<uint32_t> order(cloud.size());
  if (cloud.size() < (size_t(1) << kIndexBits)) {
    for (size_t i = 0; i < keys.size(); ++i) order[i] = uint32_t(keys[i] & ((uint64_t(1) << kIndexBits) - 1));
  } else {
    std::iota(order.begin(), order.end(), 0u);
    std::vector<uint64_t> code(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) code[i] = morton_of(i);
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
  }
  std::vector<uint64_t>().swap(keys);
  auto permute = [&](std::vector<Eigen::Vector3f>& values) {
    std::vector<Eigen::Vector3f> sorted(values.size());
    for (size_t i = 0; i < order.size(); ++i) sorted[i] = values[order[i]];
    values.swap(sorted);
  };
  permute(cloud.points);
  if (cloud.normals.size() == cloud.size()) permute(cloud.normals);
}

void add_oriented_point(OrientedSample& sample, const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
  float length = n.norm();
  if (!std::isfinite(length) || length < 1e-6f) return;
  sample.points.push_back(p);
  sample.normals.emplace_back(n / length);
}

OrientedSample oriented_sample(const PointCloud& cloud, size_t max_points) {
  OrientedSample sample;
  if (cloud.normals.size() != cloud.size() || max_points == 0) return sample;
  size_t stride = std::max<size_t>(1, (cloud.size() + max_points - 1) / max_points);
  for (size_t i = 0; i < cloud.size(); i += stride) add_oriented_point(sample, cloud.points[i], cloud.normals[i]);
  return sample;
}

void check_point_cloud(const PointCloud& cloud, const std::string& name) {
  if (cloud.empty()) throw InputError(name + ": the point cloud is empty");
  for (size_t i = 0; i < cloud.size(); ++i)
    if (!cloud.points[i].allFinite())
      throw InputError(name + ": point " + std::to_string(i) + " has a NaN or infinite coordinate");
  if (!cloud.normals.empty() && cloud.normals.size() != cloud.size())
    throw InputError(name + ": " + std::to_string(cloud.normals.size()) + " normals for " +
                     std::to_string(cloud.size()) + " points");
}

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
