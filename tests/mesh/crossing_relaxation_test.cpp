#include <gtest/gtest.h>

#include "helpers.h"
#include "mesh/crossing_relaxation.h"
#include "mesh/face_intersections.h"
#include "mesh/refinement.h"

namespace mcquad {
namespace {

//! A ball (a cube refined three times) with one vertex pushed through the
//! far side: its faces cross the far wall until the smoothing pulls it back,
//! and the rest of the ball stays where it was.
TEST(CrossingRelaxation, PullsAVertexPushedThroughTheFarWallBack) {
  QuadMesh ball = test::unit_cube();
  refine_catmull_clark(ball, 3);
  ASSERT_EQ(intersecting_face_pairs(ball).size(), 0u);
  auto pushed = ball.vertex_handle(0);
  QuadMesh::Point centre(0, 0, 0);
  for (auto v : ball.vertices()) centre += ball.point(v) / double(ball.n_vertices());
  QuadMesh::Point far = ball.point(pushed);
  for (auto v : ball.vertices())
    if ((ball.point(v) - ball.point(pushed)).norm() > (far - ball.point(pushed)).norm()) far = ball.point(v);
  QuadMesh moved = ball;
  moved.set_point(pushed, centre + 1.5 * (far - centre));
  ASSERT_GT(intersecting_face_pairs(moved).size(), 0u);

  EXPECT_EQ(relax_crossings(moved), 0u);
  EXPECT_EQ(intersecting_face_pairs(moved).size(), 0u);
  size_t unmoved = 0;
  for (auto v : moved.vertices()) unmoved += moved.point(v) == ball.point(v);
  EXPECT_GT(unmoved, moved.n_vertices() / 2) << "only the crossing's neighbourhood is smoothed";
}

//! A mesh without crossings is left exactly as it was.
TEST(CrossingRelaxation, LeavesACleanMeshAlone) {
  QuadMesh ball = test::unit_cube();
  refine_catmull_clark(ball, 2);
  QuadMesh relaxed = ball;
  EXPECT_EQ(relax_crossings(relaxed), 0u);
  for (auto v : ball.vertices()) EXPECT_EQ(relaxed.point(v), ball.point(v));
}

}  // namespace
}  // namespace mcquad
