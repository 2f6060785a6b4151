#include "mesh/crossing_tracker.h"

#include <gtest/gtest.h>

#include <random>

#include "helpers.h"
#include "mesh/face_intersections.h"

namespace mcquad {
namespace {

//! As the smoothing rounds it serves move them: a few vertices far, many a
//! little, then back where they were; every answer is the whole search's.
TEST(CrossingTracker, AnswersAsTheWholeSearchAsVerticesMove) {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  QuadMesh mesh = test::crumpled_sheets(12, 3);
  CrossingTracker tracker(mesh);
  ASSERT_EQ(tracker.pairs(mesh), intersecting_face_pairs(mesh));
  ASSERT_FALSE(tracker.pairs(mesh).empty());
  std::uniform_int_distribution<int> vertex(0, int(mesh.n_vertices()) - 1);
  for (int round = 0; round < 30; ++round) {
    std::vector<QuadMesh::Point> kept;
    for (auto v : mesh.vertices()) kept.push_back(mesh.point(v));
    const int moved = round % 5 == 4 ? int(mesh.n_vertices()) : 4;  // every fifth round moves all
    for (int k = 0; k < moved; ++k) {
      auto v = round % 5 == 4 ? mesh.vertex_handle(k) : mesh.vertex_handle(vertex(random));
      double reach = round % 5 == 4 ? 0.05 : 0.8;
      mesh.set_point(v, mesh.point(v) + reach * QuadMesh::Point(unit(random), unit(random), unit(random)));
    }
    ASSERT_EQ(tracker.pairs(mesh), intersecting_face_pairs(mesh)) << "round " << round;
    if (round % 3 == 2) {  // a move undone, as the relaxations undo one that made faces cross
      for (auto v : mesh.vertices()) mesh.set_point(v, kept[size_t(v.idx())]);
      ASSERT_EQ(tracker.pairs(mesh), intersecting_face_pairs(mesh)) << "round " << round << ", undone";
    }
  }
}

}  // namespace
}  // namespace mcquad
