#include <gtest/gtest.h>

#include <random>

#include "cells/cell_tree.h"
#include "helpers.h"
#include "mesh/close_triangle_pairs.h"
#include "mesh/face_intersections.h"
#include "metrics/mesh_metrics.h"

namespace mcquad {
namespace {

using test::crumpled_sheets;

std::vector<std::pair<int, int>> brute_force(const MeshTriangles& t, const std::vector<char>* only_faces = nullptr) {
  std::vector<std::pair<int, int>> pairs;
  for (size_t a = 0; a < t.size(); ++a)
    for (size_t b = a + 1; b < t.size(); ++b) {
      int fa = t.face[a], fb = t.face[b];
      if (fa == fb || (only_faces && !(*only_faces)[size_t(fa)] && !(*only_faces)[size_t(fb)])) continue;
      bool shared = false;
      for (int i : t.corners[a])
        for (int j : t.corners[b]) shared |= i == j;
      if (shared) continue;
      Eigen::Vector3d pa[3], pb[3];
      for (int k = 0; k < 3; ++k) pa[k] = t.corner(a, k), pb[k] = t.corner(b, k);
      if (triangles_intersect(pa, pb)) pairs.emplace_back(std::min(fa, fb), std::max(fa, fb));
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

TEST(FaceIntersections, BroadPhaseMatchesBruteForce) {
  for (unsigned seed : {1u, 2u, 3u}) {
    MeshTriangles triangles = triangulate(crumpled_sheets(12, seed));
    std::vector<std::pair<int, int>> expected = brute_force(triangles);
    ASSERT_GT(expected.size(), 20u) << "the sheets must cross";
    EXPECT_EQ(intersecting_face_pairs(triangles), expected) << "seed " << seed;
    // Only some faces: the pairs with at least one of them.
    std::vector<char> only(triangles.face.back() + 1, 0);
    for (size_t f = 0; f < only.size(); f += 3) only[f] = 1;
    EXPECT_EQ(intersecting_face_pairs(triangles, &only), brute_force(triangles, &only)) << "seed " << seed;
  }
}

//! The Verlet list of the crossing guard: as the vertices move step by step,
//! small steps reuse the list and large ones rebuild it, and every call
//! answers as the brute force does, for all faces and for some.
TEST(CloseTrianglePairs, MatchBruteForceAsTheVerticesMove) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MeshTriangles triangles = triangulate(crumpled_sheets(10, 4));
  CloseTrianglePairs close(0.2);
  size_t calls = 0;
  for (int step = 0; step < 24; ++step) {
    // Mostly small moves (the list lasts 2 of them at most); every 6th moves
    // up to half an edge, far past the list's gap.
    double reach = step % 6 == 5 ? 0.5 : 0.04;
    for (auto& p : triangles.positions) p += reach * Eigen::Vector3d(unit(random), unit(random), unit(random));
    std::vector<char> only(size_t(triangles.face.back() + 1), 0);
    for (size_t f = size_t(step) % 4; f < only.size(); f += 4) only[f] = 1;
    EXPECT_EQ(close.intersecting_face_pairs(triangles), brute_force(triangles)) << "step " << step;
    EXPECT_EQ(close.intersecting_face_pairs(triangles, &only), brute_force(triangles, &only)) << "step " << step;
    calls += 2;
  }
  EXPECT_GE(close.builds(), 4u) << "the large moves must rebuild the list";
  EXPECT_LE(close.builds() + close.refreshes(), calls / 2) << "small moves must reuse the list";
}

//! A few vertices going far (the smoothing of some turned faces, the
//! held-back vertices of a fine mesh) refresh their triangles' pairs only,
//! and every call still answers as the brute force does.
TEST(CloseTrianglePairs, AFewVerticesGoingFarRefreshOnlyTheirPairs) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  MeshTriangles triangles = triangulate(crumpled_sheets(12, 5));
  CloseTrianglePairs close(0.2);
  std::uniform_int_distribution<size_t> vertex(0, triangles.positions.size() - 1);
  for (int step = 0; step < 30; ++step) {
    // Three vertices a step jump up to an edge; the rest creep.
    for (int k = 0; k < 3; ++k) triangles.positions[vertex(random)] += Eigen::Vector3d(unit(random), unit(random), 0.3);
    for (auto& p : triangles.positions) p += 0.005 * Eigen::Vector3d(unit(random), unit(random), unit(random));
    std::vector<char> only(size_t(triangles.face.back() + 1), 0);
    for (size_t f = size_t(step) % 3; f < only.size(); f += 3) only[f] = 1;
    ASSERT_EQ(close.intersecting_face_pairs(triangles), brute_force(triangles)) << "step " << step;
    ASSERT_EQ(close.intersecting_face_pairs(triangles, &only), brute_force(triangles, &only)) << "step " << step;
  }
  EXPECT_EQ(close.builds(), 1u) << "a few far vertices must not rebuild the whole list";
  EXPECT_GE(close.refreshes(), 25u);
}

TEST(FaceIntersections, MetricsSayWhereFacesCross) {
  QuadMesh mesh = crumpled_sheets(6, 5);
  PointCloud cloud;
  for (auto v : mesh.vertices()) cloud.points.push_back(point_of(mesh, v).cast<float>());
  CellTree cells = build_cell_tree(cloud, 6);
  QualityMetrics m = measure_quality(mesh, cloud, cells, nullptr);
  std::vector<std::pair<int, int>> pairs = intersecting_face_pairs(mesh);
  ASSERT_EQ(m.intersecting_face_pairs, pairs.size());
  ASSERT_EQ(m.crossing_sites.size(), std::min(pairs.size(), QualityMetrics::kMaxCrossingSites));
  for (size_t k = 0; k < m.crossing_sites.size(); ++k)
    EXPECT_LT((m.crossing_sites[k] - 0.5 * (face_centroid(mesh, pairs[k].first) + face_centroid(mesh, pairs[k].second)))
                  .norm(),
              1e-12);
  EXPECT_EQ(to_json(m)["crossing_sites"].size(), m.crossing_sites.size());
}

}  // namespace
}  // namespace mcquad
