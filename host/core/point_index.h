#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <nanoflann.hpp>
#include <vector>

namespace mcquad {

//! A quantile (0.5: the median) of the distance from a point to its nearest
//! neighbour, over a deterministic subsample of about 2000 points (enough
//! for it). `tree` is any nanoflann index over `points` with 32-bit indices.
template <typename Tree, typename Point>
double neighbour_spacing_quantile(const std::vector<Point>& points, const Tree& tree, double quantile) {
  std::vector<double> gaps;
  size_t stride = std::max<size_t>(1, points.size() / 2000);
  for (size_t i = 0; i < points.size(); i += stride) {
    uint32_t index[2];
    typename Point::Scalar distance2[2];
    if (tree.knnSearch(points[i].data(), 2, index, distance2) == 2) gaps.push_back(std::sqrt(double(distance2[1])));
  }
  if (gaps.empty()) return 0.0;
  auto at = gaps.begin() + long(std::min(gaps.size() - 1, size_t(quantile * double(gaps.size()))));
  std::nth_element(gaps.begin(), at, gaps.end());
  return *at;
}

//! The cloud's typical point spacing: the median nearest-neighbour distance.
template <typename Tree, typename Point>
double median_neighbour_spacing(const std::vector<Point>& points, const Tree& tree) {
  return neighbour_spacing_quantile(points, tree, 0.5);
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

  //! See median_neighbour_spacing and neighbour_spacing_quantile.
  double median_spacing() const { return median_neighbour_spacing(adaptor_.points, tree_); }
  double spacing_quantile(double quantile) const {
    return neighbour_spacing_quantile(adaptor_.points, tree_, quantile);
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
