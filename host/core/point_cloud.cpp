#include "core/point_cloud.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>

#include "core/errors.h"
#include "core/morton.h"

namespace mcquad {
namespace {

//! Sorts the points of one bucket (places [first, last)) by their Morton
//! codes, ties in their present order, through the scratch arrays.
template <typename MortonOf>
void sort_bucket(std::vector<Eigen::Vector3f>& points, std::vector<Eigen::Vector3f>& normals, size_t first, size_t last,
                 const MortonOf& morton_of, std::vector<uint64_t>& keys, std::vector<Eigen::Vector3f>& scratch) {
  size_t count = last - first;
  if (count < 2) return;
  // The code above the place in the bucket: a bucket holds fewer than 2^32
  // points, and its codes share their top bits, so both fit in 64.
  keys.resize(count);
  for (size_t i = 0; i < count; ++i) keys[i] = morton_of(points[first + i]) << 32 | uint64_t(i);
  std::sort(keys.begin(), keys.end());
  auto gather = [&](std::vector<Eigen::Vector3f>& values) {
    scratch.resize(count);
    for (size_t i = 0; i < count; ++i) scratch[i] = values[first + size_t(keys[i] & 0xffffffffu)];
    std::copy(scratch.begin(), scratch.end(), values.begin() + long(first));
  };
  gather(points);
  if (!normals.empty()) gather(normals);
}

}  // namespace

void sort_spatially(PointCloud& cloud) {
  if (cloud.size() < 2) return;
  // A bucket's places take 32 bits of its sort keys.
  if (cloud.size() >= size_t(UINT32_MAX)) throw UnsupportedError("clouds of 2^32 points or more are not supported");
  // The points in the order of their 13-bit-per-axis Morton codes, ties in
  // input order. First a stable counting sort by the codes' top 15 bits
  // into 32,768 buckets (two passes over the points, one copy of them),
  // then each bucket by its codes' low 24 bits, on all cores. The passes
  // compute each point's bucket afresh rather than keep it: at 10^8 points
  // the kept buckets took 200 MB on top of the points and their copy, and
  // put the fit's peak 48 MiB over issue 18's 2.5 GiB. The sort then takes
  // 2.4 GB at most (a sort of 64-bit keys and a sorted copy took 3.2 GB)
  // and a few seconds (std::stable_sort of indices: 34 s).
  constexpr int kAxisBits = 13, kBucketBits = 15, kLowBits = 3 * kAxisBits - kBucketBits;
  // Not a structured binding: the lambda below captures `lo` (C++20 allows that, clang's C++17 does not).
  const std::pair<Eigen::Vector3f, Eigen::Vector3f> box = bounding_box(cloud);
  const Eigen::Vector3f lo = box.first, hi = box.second;
  Eigen::Vector3f scale = (hi - lo).cwiseMax(1e-30f).cwiseInverse() * float((1 << kAxisBits) - 1);
  auto morton_of = [&](const Eigen::Vector3f& p) { return morton_code((p - lo).cwiseProduct(scale)); };
  auto low_code_of = [&](const Eigen::Vector3f& p) { return morton_of(p) & ((uint64_t(1) << kLowBits) - 1); };
  const size_t n = cloud.size(), buckets = size_t(1) << kBucketBits;
  auto bucket_of = [&](const Eigen::Vector3f& p) { return size_t(morton_of(p) >> kLowBits); };
  // The points fall into kRuns runs in input order, counted and then
  // placed each on its own (on as many cores as there are): run t's points
  // of bucket b go after the earlier runs' ones, which keeps the input order
  // within a bucket whatever the number of threads.
  constexpr int kRuns = 16;
  std::vector<std::vector<size_t>> counts(size_t(kRuns), std::vector<size_t>(buckets, 0));
  auto run_of = [&](int t) { return std::make_pair(n * size_t(t) / size_t(kRuns), n * size_t(t + 1) / size_t(kRuns)); };
#pragma omp parallel for schedule(dynamic, 1)
  for (int t = 0; t < kRuns; ++t) {
    auto [first, last] = run_of(t);
    for (size_t i = first; i < last; ++i) ++counts[size_t(t)][bucket_of(cloud.points[i])];
  }
  // Each count becomes where its run's points of that bucket start.
  std::vector<size_t> offsets(buckets + 1, 0);
  for (size_t b = 0; b < buckets; ++b) {
    size_t place = offsets[b];
    for (auto& count : counts) {
      const size_t here = count[b];
      count[b] = place;
      place += here;
    }
    offsets[b + 1] = place;
  }
  const bool has_normals = cloud.normals.size() == n;
  // The normals first: their buckets come from the points in input order.
  auto scatter = [&](std::vector<Eigen::Vector3f>& values) {
    std::vector<Eigen::Vector3f> sorted(n);
#pragma omp parallel for schedule(dynamic, 1)
    for (int t = 0; t < kRuns; ++t) {
      std::vector<size_t> next = counts[size_t(t)];  // a copy: the normals and the points both start here
      auto [first, last] = run_of(t);
      for (size_t i = first; i < last; ++i) sorted[next[bucket_of(cloud.points[i])]++] = values[i];
    }
    values.swap(sorted);
  };
  if (has_normals) scatter(cloud.normals);
  scatter(cloud.points);
  std::vector<Eigen::Vector3f> no_normals;
  std::vector<Eigen::Vector3f>& normals = has_normals ? cloud.normals : no_normals;
#pragma omp parallel
  {
    std::vector<uint64_t> keys;
    std::vector<Eigen::Vector3f> scratch;
#pragma omp for schedule(dynamic, 64)
    for (long b = 0; b < long(offsets.size() - 1); ++b)
      sort_bucket(cloud.points, normals, offsets[size_t(b)], offsets[size_t(b) + 1], low_code_of, keys, scratch);
  }
}

void add_oriented_point(OrientedSample& sample, const Eigen::Vector3f& p, const Eigen::Vector3f& n) {
  float length = n.norm();
  if (!std::isfinite(length) || length < 1e-6f) return;
  sample.points.push_back(p);
  sample.normals.emplace_back(n / length);
}

size_t cloud_sample_stride(size_t points, size_t max_points) {
  return max_points > 0 ? std::max<size_t>(1, (points + max_points - 1) / max_points) : 1;
}

PointCloud strided_sample(const PointCloud& cloud, size_t max_points) {
  PointCloud sample;
  size_t stride = cloud_sample_stride(cloud.size(), max_points);
  bool normals = cloud.normals.size() == cloud.size();
  sample.points.reserve(cloud.size() / stride + 1);
  if (normals) sample.normals.reserve(cloud.size() / stride + 1);
  for (size_t i = 0; i < cloud.size(); i += stride) {
    sample.points.push_back(cloud.points[i]);
    if (normals) sample.normals.push_back(cloud.normals[i]);
  }
  return sample;
}

OrientedSample oriented_sample(const PointCloud& cloud, size_t max_points) {
  OrientedSample sample;
  if (cloud.normals.size() != cloud.size() || max_points == 0) return sample;
  size_t stride = cloud_sample_stride(cloud.size(), max_points);
  for (size_t i = 0; i < cloud.size(); i += stride) add_oriented_point(sample, cloud.points[i], cloud.normals[i]);
  return sample;
}

void sort_spatially(OrientedSample& sample) {
  PointCloud cloud;  // moved in and out: no copy
  cloud.points = std::move(sample.points);
  cloud.normals = std::move(sample.normals);
  sort_spatially(cloud);
  sample.points = std::move(cloud.points);
  sample.normals = std::move(cloud.normals);
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
