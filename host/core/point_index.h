#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <nanoflann.hpp>
#include <vector>

#include "core/quantile.h"

namespace mcquad {

//! The subsample the spacing quantiles are taken over: every point at a
//! stride giving about 2000 of them (enough for a quantile).
inline std::vector<size_t> neighbour_spacing_sample(size_t point_count) {
  std::vector<size_t> sample;
  size_t stride = std::max<size_t>(1, point_count / 2000);
  for (size_t i = 0; i < point_count; i += stride) sample.push_back(i);
  return sample;
}

//! A quantile (0.5: the median) of the distance from a point to its nearest
//! neighbour, over the subsample of neighbour_spacing_sample.
//! `second_nearest2(p)` gives the squared distance from one of the points to
//! its second nearest among them (the nearest being itself), or infinity
//! when there is none.
template <typename Point, typename SecondNearest2>
double neighbour_spacing_quantile(const std::vector<Point>& points, const SecondNearest2& second_nearest2,
                                  double quantile) {
  std::vector<double> gaps;
  for (size_t i : neighbour_spacing_sample(points.size())) {
    double d2 = double(second_nearest2(points[i]));
    if (std::isfinite(d2)) gaps.push_back(std::sqrt(d2));
  }
  return quantile_of(std::move(gaps), quantile);
}

//! Nearest-neighbour index over a vector of 3D points (nanoflann through an
//! adaptor, so the points are indexed in place, not copied). The points must
//! outlive the index and stay unchanged.
template <typename Scalar>
class PointIndex {
 public:
  using Point = Eigen::Matrix<Scalar, 3, 1>;

  explicit PointIndex(const std::vector<Point>& points, size_t leaf_size = 16)
      : adaptor_{points}, tree_(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(leaf_size)) {
    tree_.buildIndex();
  }
  // The tree refers to the adaptor inside this object: never copy or move it.
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  //! Index of the nearest point and its squared distance (-1 for an empty index).
  std::pair<long, Scalar> nearest(const Point& query) const {
    if (adaptor_.points.empty()) return {-1, Scalar(0)};
    uint32_t index = 0;
    Scalar distance2 = 0;
    nanoflann::KNNResultSet<Scalar, uint32_t> result(1);
    result.init(&index, &distance2);
    tree_.findNeighbors(result, query.data(), nanoflann::SearchParams());
    return {long(index), distance2};
  }

  //! The k nearest points (indices), nearest first.
  std::vector<size_t> k_nearest(const Point& query, size_t k) const {
    k = std::min(k, adaptor_.points.size());
    std::vector<uint32_t> found_indices(k);
    std::vector<Scalar> distances(k);
    if (k == 0) return {};
    size_t found = tree_.knnSearch(query.data(), k, found_indices.data(), distances.data());
    return std::vector<size_t>(found_indices.begin(), found_indices.begin() + found);
  }

  //! Indices of all points within `radius` of the query.
  std::vector<size_t> within(const Point& query, Scalar radius) const {
    std::vector<std::pair<uint32_t, Scalar>> matches;
    tree_.radiusSearch(query.data(), radius * radius, matches, nanoflann::SearchParams());
    std::vector<size_t> indices;
    indices.reserve(matches.size());
    for (const auto& m : matches) indices.push_back(m.first);
    return indices;
  }

  //! The squared distance from one of the points to its second nearest
  //! (the nearest other than itself), infinity when there is none.
  Scalar second_nearest_distance2(const Point& p) const {
    uint32_t index[2];
    Scalar distance2[2];
    if (tree_.knnSearch(p.data(), 2, index, distance2) < 2) return std::numeric_limits<Scalar>::infinity();
    return distance2[1];
  }
  //! See neighbour_spacing_quantile.
  double median_spacing() const { return spacing_quantile(0.5); }
  double spacing_quantile(double quantile) const {
    return neighbour_spacing_quantile(
        adaptor_.points, [this](const Point& p) { return second_nearest_distance2(p); }, quantile);
  }

 private:
  struct Adaptor {
    const std::vector<Point>& points;
    size_t kdtree_get_point_count() const { return points.size(); }
    Scalar kdtree_get_pt(size_t i, size_t dim) const { return points[i][dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  // 32-bit indices: 4 bytes a point instead of 8 (clouds stay below 2^32 points).
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<Scalar, Adaptor>, Adaptor, 3, uint32_t>;

  Adaptor adaptor_;
  Tree tree_;
};

}  // namespace mcquad
