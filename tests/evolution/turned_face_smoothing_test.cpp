// Robust mode's smoothing of the faces turned against the scan's normals
// after the evolution (evolution/turned_face_smoothing.h), through the whole
// fit as a user runs it, on issue 20's junctions: measured against the true
// surface, not against the scan's normals the smoothing itself looks at.
#include <gtest/gtest.h>

#include "evolution/evolution_fixture.h"
#include "evolution/turned_face_smoothing.h"
#include "generate/true_surface_distance.h"
#include "mesh/face_intersections.h"
#include "mesh/folds.h"
#include "mesh/quad_shape.h"
#include "metrics/surface_distance.h"

namespace mcquad {
namespace {

struct Junction {
  const char* label;
  const char* shape;
  int arms;
  double angle_degrees;
  //! Whether issue 20's bound holds: at most 0.1 % of the area facing
  //! against the true surface. The skew stars of 8, 10 and 12 once stood
  //! here; since the blocks' acute crotches are searched in the cloud they
  //! keep under 0.09 % turned without the smoothing, too little to test it
  //! on, and the planar 7 and the 20-degree fan took their place. Since the
  //! bones at moved forks are widened (skeleton/acute_junctions.h) the
  //! planar 5 and the 30-degree fan turn 0.04 and 0.004 % without the
  //! smoothing, and the planar 8 (0.19 %) took their place; the 20-degree
  //! fan's smoothing no longer halves what it turns (0.21 -> 0.27 %,
  //! docs/HARD_CASES.md, "Creases short of the crotch") and it left. Since
  //! the rings keep their port's tilt (mesh/initial_mesh.cpp) the planar 7
  //! turns 0.081 % without the smoothing; the 40-degree fan (0.205 -> 0.021 %)
  //! took its place, and the 20-degree fan came back (0.681 -> 0.208 %,
  //! halved and more; `mcquad fit --turned-face-rounds 0`, then the
  //! default, and `mcquad metrics --surface`). Since limbs that hug a
  //! forking pair move with it (skeleton/acute_junctions.h) both fans turn
  //! under 0.03 % without the smoothing, and random tree 2 took their place
  //! (0.648 -> 0.118 %, 40,000 points; its acute pairs are kept for want of
  //! room).
  bool within_bound;
  uint64_t seed = 1;
};

void PrintTo(const Junction& c, std::ostream* os) { *os << c.label; }

//! Junctions whose creases leave more than 0.1 % of the area turned without
//! the smoothing (docs/HARD_CASES.md).
const Junction kJunctions[] = {{"planar_8", "planar-star", 8, 0, true},
                               {"random_tree_2", "random-tree", 0, 0, false, 2}};

struct Fitted {
  FitResult fit;
  TrueSurfaceDistance truth;
  double coverage_p95 = 0;
};

Fitted fit(const GeneratedShape& shape, BackendKind backend, unsigned turned_face_rounds) {
  FitOptions options;
  options.backend = backend;
  options.evolution.turned_face_rounds = turned_face_rounds;
  Fitted f{run_fit(FitInput{shape.cloud, shape.skeleton}, options), {}, 0};
  f.truth = measure_true_surface_distance(f.fit.mesh, shape.surface);
  f.coverage_p95 = cloud_to_mesh_relative_to_local_radius(f.fit.mesh, shape.cloud, shape.surface).p95;
  return f;
}

class TurnedFaces : public ::testing::TestWithParam<std::tuple<Junction, BackendKind>> {};

//! Without the smoothing the creases keep more than issue 20's 0.1 % of the
//! area turned against the true surface; with it at most 0.1 % where that
//! holds (else at most half of what they had), with no face pair
//! crossing, no fold, no quad under the guard's least scaled Jacobian, and
//! the cloud still covered.
TEST_P(TurnedFaces, SmoothingTurnsTheCreasesFacesOut) {
  const auto& [c, kind] = GetParam();
  REQUIRE_BACKEND(device_found, kind);  // skips, or fails where CI requires an OpenCL device
  ShapeOptions options;
  options.arms = c.arms;
  options.angle_degrees = c.angle_degrees;
  options.seed = c.seed;
  GeneratedShape shape = test::small_shape(c.shape, 40000, options);
  Fitted off = fit(shape, kind, 0);
  Fitted on = fit(shape, kind, EvolutionParameters().turned_face_rounds);
  EXPECT_GT(off.truth.inward_area_fraction, 0.001) << "a case the smoothing has nothing to do on proves nothing";
  EXPECT_FALSE(off.fit.report.evolution->turned_faces.has_value());
  ASSERT_TRUE(on.fit.report.evolution->turned_faces.has_value());
  const TurnedFaceSmoothing& smoothing = *on.fit.report.evolution->turned_faces;
  EXPECT_LT(smoothing.faces_after, smoothing.faces_before);
  EXPECT_LT(smoothing.area_after, smoothing.area_before);
  // Measured against the true surface: within the bound where that holds, else at least halved.
  if (c.within_bound) {
    EXPECT_LE(on.truth.inward_area_fraction, 0.001) << "share of the area facing against the true surface";
  } else {
    EXPECT_LE(on.truth.inward_area_fraction, 0.5 * off.truth.inward_area_fraction);
  }
  EXPECT_EQ(intersecting_face_pairs(on.fit.mesh).size(), 0u);
  EXPECT_EQ(folded_edges(on.fit.mesh), 0u);
  EXPECT_GE(measure_quad_shape(on.fit.mesh).min_scaled_jacobian, 0.3 - 1e-3);
  EXPECT_LE(on.coverage_p95, 0.05);
  // The creases come out a little rounded, no more.
  EXPECT_LE(on.truth.relative.mean, off.truth.relative.mean + 0.002);
}

INSTANTIATE_TEST_SUITE_P(Issue20, TurnedFaces,
                         ::testing::Combine(::testing::ValuesIn(kJunctions),
                                            ::testing::ValuesIn(test::backend_kinds())),
                         test::case_and_backend_label<Junction>);

//! Without normals there is nothing to tell a turned face by: the mesh is
//! left as it is, and the report says nothing of it.
TEST(TurnedFaceSmoothing, LeavesAMeshAloneWithoutTheScansNormals) {
  test::Fixture f("t-shape", 5000);
  QuadMesh mesh = f.initial.mesh;
  const OrientedSample none;
  TurnedFaceSmoothing result = smooth_turned_faces(mesh, f.arrays, ScanOrientation(none), 20);
  EXPECT_EQ(result.rounds, 0);
  EXPECT_EQ(result.faces_before, 0u);
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v), f.initial.mesh.point(v));
}

//! Faces turned against the scan get smoothed, and a mesh that faces out
//! everywhere is not touched.
TEST(TurnedFaceSmoothing, TouchesOnlyTurnedFaces) {
  test::Fixture f("t-shape", 5000);
  OrientedSample scan = oriented_sample(f.shape.cloud);
  ASSERT_FALSE(scan.empty());
  QuadMesh mesh = f.initial.mesh;
  TurnedFaceSmoothing untouched = smooth_turned_faces(mesh, f.arrays, ScanOrientation(scan), 20);
  EXPECT_EQ(untouched.faces_before, 0u) << "the rough mesh faces out everywhere";
  EXPECT_EQ(untouched.rounds, 0);
  for (auto v : mesh.vertices()) EXPECT_EQ(mesh.point(v), f.initial.mesh.point(v));
  // The same mesh against a scan whose normals all point in: every face is
  // turned, and the guard lets no round turn one more than 90 degrees.
  OrientedSample inverted = scan;
  for (auto& n : inverted.normals) n = -n;
  TurnedFaceSmoothing all = smooth_turned_faces(mesh, f.arrays, ScanOrientation(inverted), 3);
  EXPECT_EQ(all.faces_before, mesh.n_faces());
  EXPECT_EQ(all.rounds, 3);
  EXPECT_EQ(intersecting_face_pairs(mesh).size(), 0u);
  EXPECT_EQ(folded_edges(mesh), 0u);
}

}  // namespace
}  // namespace mcquad
