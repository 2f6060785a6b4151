// SortedPointTree against a search through every point: the same nearest
// point (the first of equally near ones) and distance, on sorted and
// unsorted clouds, with duplicates, flat patches and sizes that leave the
// tree's last leaves padded.
#include "core/sorted_point_tree.h"

#include <gtest/gtest.h>

#include <random>

#include "core/point_cloud.h"

namespace mcquad {
namespace {

std::pair<long, float> nearest_by_brute_force(const std::vector<Eigen::Vector3f>& points, const Eigen::Vector3f& q) {
  std::pair<long, float> best{-1, INFINITY};
  for (size_t i = 0; i < points.size(); ++i) {
    float d2 = (points[i] - q).squaredNorm();
    if (d2 < best.second) best = {long(i), d2};
  }
  return best;
}

void expect_as_brute_force(const std::vector<Eigen::Vector3f>& points, unsigned seed, const std::string& what) {
  SortedPointTree tree(points);
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> coordinate(-1.5f, 1.5f);
  for (int k = 0; k < 300; ++k) {
    // Half the queries on the points themselves (distance 0, ties among duplicates).
    Eigen::Vector3f q = k % 2 && !points.empty()
                            ? points[random() % points.size()]
                            : Eigen::Vector3f(coordinate(random), coordinate(random), coordinate(random));
    EXPECT_EQ(tree.nearest(q), nearest_by_brute_force(points, q)) << what << " query " << k;
  }
}

std::vector<Eigen::Vector3f> sphere_with_duplicates_and_a_flat_patch(size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::normal_distribution<float> gauss;
  std::vector<Eigen::Vector3f> points;
  for (size_t i = 0; i < count; ++i) {
    Eigen::Vector3f p(gauss(random), gauss(random), gauss(random));
    points.push_back(p.normalized());
    if (i % 7 == 0) points.push_back(points.back());                     // duplicates
    if (i % 5 == 0) points.emplace_back(p.x() * 0.1f, p.y() * 0.1f, 0);  // a flat patch, shared z
  }
  return points;
}

TEST(SortedPointTree, FindsTheNearestPointAsASearchThroughEveryPoint) {
  for (size_t count : {1, 7, 8, 9, 100, 1000, 5000}) {
    PointCloud cloud;
    cloud.points = sphere_with_duplicates_and_a_flat_patch(count, unsigned(count));
    expect_as_brute_force(cloud.points, 1, "unsorted " + std::to_string(count));
    sort_spatially(cloud);
    expect_as_brute_force(cloud.points, 2, "sorted " + std::to_string(count));
  }
}

TEST(SortedPointTree, AnEmptyTreeFindsNothing) {
  std::vector<Eigen::Vector3f> none;
  EXPECT_EQ(SortedPointTree(none).nearest(Eigen::Vector3f::Zero()).first, -1);
}

}  // namespace
}  // namespace mcquad
