// The junctions' inflation (mesh/junction_inflation.h), seen through the
// initial mesh it is part of: round an 8-arm star's node the mesh moves
// toward the true surface, and stays embedded and inside.
#include <gtest/gtest.h>

#include "helpers.h"
#include "mesh/face_intersections.h"
#include "mesh/initial_mesh.h"
#include "skeleton/bone_assignment.h"

namespace mcquad {
namespace {

//! Mean depth below the true surface, over the vertices within `reach` of
//! `center`, in the arms' radius.
double mean_depth_near(const QuadMesh& mesh, const TubeSurface& surface, const Eigen::Vector3d& center, double reach,
                       double radius) {
  double sum = 0;
  int count = 0;
  for (auto v : mesh.vertices()) {
    const auto& q = mesh.point(v);
    const Eigen::Vector3d p(q[0], q[1], q[2]);
    if ((p - center).norm() > reach) continue;
    sum += -surface.signed_distance(p) / radius;
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

TEST(JunctionInflation, MovesTheMeshRoundAJunctionTowardTheTrueSurface) {
  ShapeOptions star;
  star.arms = 8;
  const auto [shape, graph, bones] = test::ShapeWithBones("star", 30000, star);
  // The blocks at the tubes' start fraction, to see the inflation alone (a
  // block built nearer the cloud, initial_mesh.h's block_fraction, already
  // starts the hub 0.26 r deep instead of 0.30; inflated, 0.22 either way).
  InitialMeshOptions on;
  on.block_fraction = on.start_fraction;
  InitialMeshOptions off = on;
  off.junction_inflation = 0;
  InitialMesh plain = build_initial_mesh(graph, bones, shape.cloud, off, "star");
  InitialMesh inflated = build_initial_mesh(graph, bones, shape.cloud, on, "star");
  const Eigen::Vector3d node = graph.positions[0];  // the generator's hub
  ASSERT_EQ(graph.kind(0), NodeKind::kJunction);
  const double radius = 0.8, reach = 2.0 * radius;
  const double before = mean_depth_near(plain.mesh, shape.surface, node, reach, radius);
  const double after = mean_depth_near(inflated.mesh, shape.surface, node, reach, radius);
  // Measured 0.30 -> 0.22 of r within two radii of the node: the rough mesh
  // starts 0.3 r inside along the arms and deeper round the node; inflated,
  // the hub starts 0.15 r inside as far as its rays reach.
  EXPECT_LT(after, 0.8 * before) << before << " -> " << after;
  EXPECT_GT(after, 0.0) << "still inside the cloud";
  EXPECT_EQ(intersecting_face_pairs(inflated.mesh).size(), 0u);
  for (auto v : inflated.mesh.vertices()) {
    const auto& q = inflated.mesh.point(v);
    EXPECT_LT(shape.surface.signed_distance(Eigen::Vector3d(q[0], q[1], q[2])), 0.0) << "vertex " << v.idx();
  }
}

}  // namespace
}  // namespace mcquad
