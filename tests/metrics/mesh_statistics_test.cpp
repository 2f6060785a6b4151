#include <gtest/gtest.h>

#include "helpers.h"
#include "metrics/mesh_statistics.h"
#include "metrics/winding_number.h"

namespace mcquad {
namespace {

TEST(MeshStatistics, ACubeIsAClosedSphereOfEightCornersOfValenceThree) {
  MeshStatistics s = mesh_statistics(test::unit_cube());
  EXPECT_EQ(s.vertices, 8u);
  EXPECT_EQ(s.faces, 6u);
  EXPECT_EQ(s.quads, 6u);
  EXPECT_EQ(s.edges, 12u);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_EQ(s.boundary_loops, 0u);
  EXPECT_EQ(s.components, 1u);
  EXPECT_EQ(s.irregular_vertices, 8u) << "every corner has valence 3";
  EXPECT_EQ(s.non_manifold_vertices, 0u);
  EXPECT_DOUBLE_EQ(s.quad_fraction, 1.0);
}

TEST(MeshStatistics, AnOpenBoxHasOneBoundaryLoopRoundItsRim) {
  QuadMesh box = test::unit_cube();
  box.request_face_status();
  box.request_edge_status();
  box.request_vertex_status();
  box.delete_face(box.face_handle(1), false);  // the top, z = 1
  box.garbage_collection();
  MeshStatistics s = mesh_statistics(box);
  EXPECT_EQ(s.faces, 5u);
  EXPECT_EQ(s.boundary_loops, 1u);
  EXPECT_EQ(s.euler_characteristic, 1);
  std::vector<Eigen::Vector3d> centres = boundary_loop_centres(box);
  ASSERT_EQ(centres.size(), 1u);
  EXPECT_TRUE(centres[0].isApprox(Eigen::Vector3d(0.5, 0.5, 1.0))) << centres[0].transpose();
}

TEST(WindingNumber, OneInsideZeroOutsideMinusOneInsideOut) {
  QuadMesh cube = test::unit_cube(), inside_out = test::unit_cube(true);
  for (const Eigen::Vector3d& inside : {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(0.01, 0.9, 0.2)}) {
    EXPECT_NEAR(winding_number(cube, inside), 1.0, 1e-9);
    EXPECT_NEAR(winding_number(inside_out, inside), -1.0, 1e-9);
  }
  for (const Eigen::Vector3d& outside : {Eigen::Vector3d(2, 0.5, 0.5), Eigen::Vector3d(-0.01, 0.5, 0.5)}) {
    EXPECT_NEAR(winding_number(cube, outside), 0.0, 1e-9);
    EXPECT_NEAR(winding_number(inside_out, outside), 0.0, 1e-9);
  }
}

}  // namespace
}  // namespace mcquad
