#include <gtest/gtest.h>

#include <mutex>
#include <random>

#include "helpers.h"
#include "mesh/face_intersections.h"
#include "mesh/triangle_neighbourhoods.h"
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

//! Points above a flat grid's vertices, and beyond its corners, are exactly
//! as near every triangle around the vertex: the tree, with any of them as
//! the hint or none, and the neighbourhood lists, answer the lowest index
//! (the reach for the uncovered cloud would otherwise pull other corners
//! when its queries were split among another number of threads).
TEST(TriangleTree, OfEquallyNearTrianglesTheLowestWhateverTheHint) {
  QuadMesh mesh;
  test::add_quad_grid(mesh, 6, [](int i, int j) { return QuadMesh::Point(i, j, 0.0); });
  MeshTriangles triangles = triangulate(mesh);
  TriangleTree tree(triangles);
  TriangleNeighbourhoods neighbourhoods(tree, 64 * triangles.size());
  std::vector<Eigen::Vector3d> queries;
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 6; ++j) queries.emplace_back(i, j, 0.25 + 0.1 * (i + j));
  queries.emplace_back(-1.0, -1.0, 0.5);
  queries.emplace_back(7.0, 7.5, -0.5);
  size_t ties = 0;
  for (const Eigen::Vector3d& p : queries) {
    double best = INFINITY;
    std::vector<long> equally_near;
    for (size_t t = 0; t < triangles.size(); ++t) {
      const double d = tree.triangle_distance(p, t);
      if (d < best) best = d, equally_near.clear();
      if (d == best) equally_near.push_back(long(t));
    }
    const long lowest = equally_near.front();
    ties += equally_near.size() > 1;
    EXPECT_EQ(tree.nearest(p).second, lowest);
    for (long hint : equally_near) {
      EXPECT_EQ(tree.nearest(p, hint).second, lowest) << "hint " << hint;
      EXPECT_EQ(neighbourhoods.nearest(p, hint).second, lowest) << "hint " << hint;
    }
  }
  EXPECT_GT(ties, queries.size() / 2) << "no ties prove nothing";
}

TEST(TriangleTree, OverlapQueryFindsExactlyTheOverlappingBoxes) {
  MeshTriangles triangles = triangulate(folded_sheet(10, 4));
  TriangleTree tree(triangles);
  for (size_t t = 0; t < triangles.size(); t += 7) {
    std::vector<size_t> found, expected;
    tree.for_each_within_gap(tree.box(t), 0.0f, [&](size_t other) { found.push_back(other); });
    for (size_t other = 0; other < triangles.size(); ++other)
      if (tree.box(other).intersects(tree.box(t))) expected.push_back(other);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected) << "triangle " << t;
  }
}

TEST(TriangleTree, PairsWithinAGapAreExactlyThoseOfAllPairs) {
  MeshTriangles triangles = triangulate(folded_sheet(12, 5));
  TriangleTree tree(triangles);
  for (float gap : {0.0f, 0.3f, 1.5f})
    for (size_t parallel_above : {size_t(8192), size_t(16)}) {
      std::vector<std::pair<size_t, size_t>> found, expected;
      std::mutex lock;
      tree.for_each_overlapping_pair(
          nullptr,
          [&](size_t a, size_t b, int) {
            std::lock_guard<std::mutex> guard(lock);
            found.emplace_back(a, b);
          },
          parallel_above, gap);
      for (size_t a = 0; a < triangles.size(); ++a)
        for (size_t b = a + 1; b < triangles.size(); ++b) {
          const TriangleTree::Box &x = tree.box(a), &y = tree.box(b);
          if ((x.min().array() <= y.max().array() + gap).all() && (y.min().array() <= x.max().array() + gap).all())
            expected.emplace_back(a, b);
        }
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, expected) << "gap " << gap << ", parallel above " << parallel_above;
    }
}

//! A tree refitted after some corners moved answers as a tree built at the
//! new positions: the same boxes, the same triangles within a gap of a box,
//! the same nearest triangles (the order it was built in stays).
TEST(TriangleTree, RefittedAfterMovesAnswersAsANewTree) {
  MeshTriangles triangles = triangulate(folded_sheet(12, 6));
  TriangleTree refitted(triangles);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jump(-1.5, 1.5);
  for (int round = 0; round < 3; ++round) {
    std::vector<char> moved_vertex(triangles.positions.size(), 0);
    for (size_t v = size_t(round); v < triangles.positions.size(); v += 9) {
      triangles.positions[v] += Eigen::Vector3d(jump(random), jump(random), jump(random));
      moved_vertex[v] = 1;
    }
    std::vector<char> moved(triangles.size(), 0);
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) moved[t] |= moved_vertex[size_t(triangles.corners[t][size_t(k)])];
    refitted.refit(moved);
    TriangleTree fresh(triangles);
    for (size_t t = 0; t < triangles.size(); ++t) {
      ASSERT_TRUE(refitted.box(t).min() == fresh.box(t).min() && refitted.box(t).max() == fresh.box(t).max());
      if (t % 5 != 0) continue;
      std::vector<size_t> found, expected;
      refitted.for_each_within_gap(fresh.box(t), 0.4f, [&](size_t other) { found.push_back(other); });
      fresh.for_each_within_gap(fresh.box(t), 0.4f, [&](size_t other) { expected.push_back(other); });
      std::sort(found.begin(), found.end());
      std::sort(expected.begin(), expected.end());
      EXPECT_EQ(found, expected) << "round " << round << ", triangle " << t;
      ASSERT_FALSE(expected.empty());
      Eigen::Vector3d p = triangles.centroid(t) + Eigen::Vector3d(0.2, -0.3, 0.5);
      EXPECT_EQ(refitted.nearest(p), fresh.nearest(p)) << "round " << round << ", triangle " << t;
    }
  }
}

//! With the lists (kLeastQueriesPerTriangle queries a triangle) and without
//! them (one a triangle: every query descends the tree), the same distances.
TEST(TriangleNeighbourhoods, NearestMatchesTheTreeAlongAWalkWithJumps) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    MeshTriangles triangles = triangulate(folded_sheet(14, seed));
    TriangleTree tree(triangles);
    const double per_triangle = seed < 4 ? TriangleNeighbourhoods::kLeastQueriesPerTriangle : 1.0;
    TriangleNeighbourhoods neighbourhoods(tree, size_t(per_triangle * double(triangles.size())));
    std::mt19937 random(seed + 20);
    std::uniform_real_distribution<double> step(-0.3, 0.3), coordinate(-6.0, 20.0);
    Eigen::Vector3d p(5, 5, 0);
    long hint = -1;
    for (int q = 0; q < 2000; ++q) {
      // Mostly small steps near the sheet, as a sorted cloud's points come; now and then a jump.
      if (q % 50 == 49)
        p = Eigen::Vector3d(coordinate(random), coordinate(random), 0.3 * coordinate(random));
      else
        p += Eigen::Vector3d(step(random), step(random), step(random));
      auto [distance, triangle] = neighbourhoods.nearest(p, hint);
      ASSERT_GE(triangle, 0);
      EXPECT_DOUBLE_EQ(distance, tree.nearest(p).first) << "seed " << seed << ", query " << q;
      EXPECT_DOUBLE_EQ(distance, tree.triangle_distance(p, size_t(triangle)));
      hint = triangle;
    }
  }
}

TEST(TriangleTree, EmptyMeshHasNoNearestTriangle) {
  MeshTriangles none;
  TriangleTree tree(none);
  EXPECT_EQ(tree.nearest(Eigen::Vector3d::Zero()).second, -1);
}

}  // namespace
}  // namespace mcquad
