#include <gtest/gtest.h>

#include <random>

#include "helpers.h"
#include "mesh/face_intersections.h"
#include "mesh/triangle_tree.h"

namespace mcquad {
namespace {

//! A jittered, folded quad sheet: triangles of uneven size in every direction.
QuadMesh folded_sheet(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.35, 0.35);
  QuadMesh mesh;
  test::add_quad_grid(mesh, n, [&](int i, int j) {
    double x = i + jitter(random), y = j + jitter(random);
    return QuadMesh::Point(x, y, 2.0 * std::sin(0.6 * x) + jitter(random));
  });
  return mesh;
}

TEST(PointTriangleDistance, KnownAnswersInEveryRegion) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // Above the face: the height.
  EXPECT_DOUBLE_EQ(point_triangle_distance({0.5, 0.5, 3}, a, b, c), 3.0);
  // Beyond a corner: the distance to it.
  EXPECT_DOUBLE_EQ(point_triangle_distance({-3, -4, 0}, a, b, c), 5.0);
  EXPECT_NEAR(point_triangle_distance({3, 0, 0}, a, b, c), 1.0, 1e-15);
  // Beside an edge: the distance to the edge's line (the hypotenuse here).
  EXPECT_NEAR(point_triangle_distance({2, 2, 0}, a, b, c), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(point_triangle_distance({1, -1, 1}, a, b, c), std::sqrt(2.0), 1e-15);
  // On the triangle: zero.
  EXPECT_NEAR(point_triangle_distance({0.3, 0.4, 0}, a, b, c), 0.0, 1e-15);
}

TEST(TriangleTree, NearestMatchesBruteForceNearAndFar) {
  for (unsigned seed : {1u, 2u, 3u}) {
    MeshTriangles triangles = triangulate(folded_sheet(14, seed));
    TriangleTree tree(triangles);
    std::mt19937 random(seed + 10);
    std::uniform_real_distribution<double> coordinate(-6.0, 20.0);
    for (int q = 0; q < 400; ++q) {
      Eigen::Vector3d p(coordinate(random), coordinate(random), 0.3 * coordinate(random));
      double expected = INFINITY;
      for (size_t t = 0; t < triangles.size(); ++t)
        expected = std::min(expected, point_triangle_distance(p, triangles.corner(t, 0), triangles.corner(t, 1),
                                                              triangles.corner(t, 2)));
      auto [distance, triangle] = tree.nearest(p);
      ASSERT_GE(triangle, 0);
      EXPECT_DOUBLE_EQ(distance, expected) << "seed " << seed << ", query " << q;
    }
  }
}

TEST(TriangleTree, OverlapQueryFindsExactlyTheOverlappingBoxes) {
  MeshTriangles triangles = triangulate(folded_sheet(10, 4));
  TriangleTree tree(triangles);
  for (size_t t = 0; t < triangles.size(); t += 7) {
    std::vector<size_t> found, expected;
    tree.for_each_overlapping(tree.box(t), [&](size_t other) { found.push_back(other); });
    for (size_t other = 0; other < triangles.size(); ++other)
      if (tree.box(other).intersects(tree.box(t))) expected.push_back(other);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected) << "triangle " << t;
  }
}

TEST(TriangleTree, EmptyMeshHasNoNearestTriangle) {
  MeshTriangles none;
  TriangleTree tree(none);
  EXPECT_EQ(tree.nearest(Eigen::Vector3d::Zero()).second, -1);
}

}  // namespace
}  // namespace mcquad
