// The rough mesh's badly shaped quads relaxed (mesh/quad_relaxation.h).
#include "mesh/quad_relaxation.h"

#include <gtest/gtest.h>

#include "helpers.h"
#include "mesh/face_intersections.h"
#include "mesh/folds.h"
#include "mesh/quad_shape.h"
#include "mesh/refinement.h"

namespace mcquad {
namespace {

//! A cube refined twice (Catmull-Clark: a rounded box of 96 quads).
QuadMesh rounded_box() {
  QuadMesh mesh = test::unit_cube();
  refine_catmull_clark(mesh, 2);
  return mesh;
}

//! A regular vertex pushed most of the way toward the far corner of one of
//! its quads, which is left with a corner near 180 degrees.
QuadMesh box_with_a_poor_quad() {
  QuadMesh mesh = rounded_box();
  for (auto v : mesh.vertices()) {
    if (mesh.valence(v) != 4) continue;
    auto f = *mesh.vf_range(v).begin();
    auto h = mesh.halfedge_handle(f);
    while (mesh.from_vertex_handle(h) != v) h = mesh.next_halfedge_handle(h);
    auto far = mesh.to_vertex_handle(mesh.next_halfedge_handle(h));
    mesh.set_point(v, mesh.point(v) + 0.8 * (mesh.point(far) - mesh.point(v)));
    break;
  }
  return mesh;
}

TEST(QuadRelaxation, RaisesAPoorQuadWithoutCrossingOrFolding) {
  QuadMesh mesh = box_with_a_poor_quad();
  ASSERT_LT(measure_quad_shape(mesh).min_scaled_jacobian, 0.3);
  size_t crossings = intersecting_face_pairs(mesh).size(), folds = folded_edges(mesh);
  EXPECT_EQ(relax_poor_quads(mesh, 0.3), 0u);
  EXPECT_GE(measure_quad_shape(mesh).min_scaled_jacobian, 0.3);
  EXPECT_LE(intersecting_face_pairs(mesh).size(), crossings);
  EXPECT_LE(folded_edges(mesh), folds);
}

TEST(QuadRelaxation, LeavesAWellShapedMeshAlone) {
  QuadMesh mesh = rounded_box();
  ASSERT_GE(measure_quad_shape(mesh).min_scaled_jacobian, 0.3);
  QuadMesh before = mesh;
  EXPECT_EQ(relax_poor_quads(mesh, 0.3), 0u);
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v), before.point(v));
}

TEST(QuadRelaxation, StopsAtItsRoundLimit) {
  QuadMesh mesh = box_with_a_poor_quad();
  QuadMesh before = mesh;
  EXPECT_GT(relax_poor_quads(mesh, 0.3, 0), 0u) << "no round: the poor quad stays";
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v), before.point(v));
}

}  // namespace
}  // namespace mcquad
