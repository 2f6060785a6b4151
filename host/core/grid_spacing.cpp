#include "core/grid_spacing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "core/grid_cells.h"
#include "core/point_index.h"
#include "core/quantile.h"

namespace mcquad {
namespace {

//! The two smallest squared distances seen so far.
struct TwoNearest {
  float first = std::numeric_limits<float>::infinity(), second = std::numeric_limits<float>::infinity();
  void offer(float d2) {
    if (d2 < first) {
      second = first;
      first = d2;
    } else if (d2 < second) {
      second = d2;
    }
  }
  void merge(const TwoNearest& other) {
    offer(other.first);
    offer(other.second);
  }
};

// The squared distance as nanoflann's L2_Simple_Adaptor<float> sums it, so
// the quantile is the tree's to the last bit.
float squared_distance(const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
  float result = 0;
  for (int k = 0; k < 3; ++k) {
    float diff = a[k] - b[k];
    result += diff * diff;
  }
  return result;
}

//! One pass: for every query, the two nearest points within its 27 cells.
std::vector<TwoNearest> two_nearest_in_cells(const std::vector<Eigen::Vector3f>& points,
                                             const std::vector<size_t>& queries, const GridCells& grid) {
  std::unordered_map<uint64_t, std::vector<uint32_t>> queries_near;  // cell -> queries whose 27 cells hold it
  for (size_t q = 0; q < queries.size(); ++q) {
    const GridCells::Cell cell = grid.cell_of(points[queries[q]]);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const GridCells::Cell next{cell[0] + dx, cell[1] + dy, cell[2] + dz};
          if (GridCells::exists(next)) queries_near[GridCells::key(next)].push_back(uint32_t(q));
        }
  }
  std::vector<TwoNearest> nearest(queries.size());
#pragma omp parallel
  {
    std::vector<TwoNearest> mine(queries.size());
#pragma omp for schedule(static) nowait
    for (size_t i = 0; i < points.size(); ++i) {
      auto found = queries_near.find(grid.key_of(points[i]));
      if (found == queries_near.end()) continue;
      for (uint32_t q : found->second) mine[q].offer(squared_distance(points[queries[q]], points[i]));
    }
#pragma omp critical
    for (size_t q = 0; q < queries.size(); ++q) nearest[q].merge(mine[q]);  // minima: any order gives the same
  }
  return nearest;
}

}  // namespace

double grid_spacing_quantile(const std::vector<Eigen::Vector3f>& points, double quantile) {
  if (points.size() < 2) return 0.0;
  const auto [lo, hi] = box_of(points);
  std::vector<size_t> all_queries = neighbour_spacing_sample(points.size());
  std::vector<float> second(all_queries.size(), std::numeric_limits<float>::infinity());
  // A start near the typical spacing of a surface sample: the box's
  // diagonal over the square root of the count.
  double extent = std::max((hi - lo).norm(), 1e-30);
  double radius = std::max(2.0 * extent / std::sqrt(double(points.size())), extent / double(GridCells::kAxisCells - 2));
  std::vector<size_t> open(all_queries.size());
  for (size_t q = 0; q < open.size(); ++q) open[q] = q;
  while (!open.empty()) {
    std::vector<size_t> queries(open.size());
    for (size_t k = 0; k < open.size(); ++k) queries[k] = all_queries[open[k]];
    std::vector<TwoNearest> nearest = two_nearest_in_cells(points, queries, GridCells{lo, radius});
    std::vector<size_t> still_open;
    for (size_t k = 0; k < open.size(); ++k) {
      // Exact once the second nearest lies within the radius (the 27 cells
      // hold the whole ball), or once the cells hold the whole box.
      bool whole_box = radius >= extent;
      if (double(nearest[k].second) <= radius * radius || whole_box)
        second[open[k]] = nearest[k].second;
      else
        still_open.push_back(open[k]);
    }
    open = std::move(still_open);
    radius *= 2;
  }
  std::vector<double> gaps;
  gaps.reserve(second.size());
  for (float d2 : second)
    if (std::isfinite(d2)) gaps.push_back(std::sqrt(double(d2)));
  return quantile_of(std::move(gaps), quantile);
}

}  // namespace mcquad
