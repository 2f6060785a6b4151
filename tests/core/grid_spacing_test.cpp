// grid_spacing_quantile against the kd-tree's spacing quantile: the same
// value to the last bit, on clouds with duplicates, outliers far off, a
// tenfold density change, and the few-point corner cases.
#include "core/grid_spacing.h"

#include <gtest/gtest.h>

#include <random>

#include "core/point_index.h"
#include "generate/shapes.h"

namespace mcquad {
namespace {

void expect_as_the_tree(const std::vector<Eigen::Vector3f>& points, const std::string& what) {
  PointIndex<float> index(points);
  for (double quantile : {0.1, 0.5, 0.9})
    EXPECT_EQ(grid_spacing_quantile(points, quantile), index.spacing_quantile(quantile)) << what << " q " << quantile;
}

TEST(GridSpacing, IsTheTreesQuantileExactly) {
  ShapeOptions dense;
  dense.points = 60000;
  expect_as_the_tree(generate_shape("t-shape", dense).cloud.points, "T");
  ShapeOptions defects = dense;
  defects.outliers = 0.01;
  defects.density_ratio = 10;
  defects.holes = 4;
  expect_as_the_tree(generate_shape("y-fork", defects).cloud.points, "Y with outliers, density, holes");

  std::vector<Eigen::Vector3f> duplicated = generate_shape("tube", ShapeOptions{}).cloud.points;
  duplicated.insert(duplicated.end(), duplicated.begin(), duplicated.begin() + 5000);
  expect_as_the_tree(duplicated, "tube with duplicates");

  std::vector<Eigen::Vector3f> far_apart{{0, 0, 0}, {1e6f, 0, 0}, {0, 3, 0}};  // one point far off
  expect_as_the_tree(far_apart, "three points");
  std::vector<Eigen::Vector3f> same(100, Eigen::Vector3f(1, 2, 3));
  expect_as_the_tree(same, "one point a hundred times");
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(-1e-3f, 1e-3f);
  std::vector<Eigen::Vector3f> tiny;
  for (int k = 0; k < 5000; ++k) tiny.emplace_back(u(random), u(random), u(random));
  expect_as_the_tree(tiny, "a tiny box");
}

TEST(GridSpacing, FewPoints) {
  EXPECT_EQ(grid_spacing_quantile({}, 0.5), 0.0);
  EXPECT_EQ(grid_spacing_quantile({Eigen::Vector3f(1, 1, 1)}, 0.5), 0.0);
}

}  // namespace
}  // namespace mcquad
