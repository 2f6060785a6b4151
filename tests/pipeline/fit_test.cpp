// The whole fit from memory (run_fit), on generated shapes.
#include <gtest/gtest.h>

#include "generate/true_surface_distance.h"
#include "helpers.h"
#include "mesh/face_intersections.h"
#include "metrics/mesh_statistics.h"
#include "pipeline/fit.h"

namespace mcquad {
namespace {

FitResult fit_finer(const GeneratedShape& shape, bool coarse_to_fine) {
  FitOptions options;
  options.backend = BackendKind::kSerial;
  options.initial.target_vertices = 4000;
  options.evolution.coarse_to_fine = coarse_to_fine;
  return run_fit(FitInput{shape.cloud, shape.skeleton, "y-fork.ply", "y-fork.skeleton.obj"}, options);
}

//! Finer than the default resolution, robust mode evolves the default mesh
//! first, refines the fit and evolves again: the same mesh topology as the
//! finer rough mesh evolved from the start, no crossing faces, and closer
//! to the cloud, since every vertex of the finer mesh starts within reach.
TEST(CoarseToFine, AFinerFitStartsFromTheDefaultOnesFitAndEndsCloser) {
  ShapeOptions y30;
  y30.angle_degrees = 30;
  GeneratedShape shape = test::small_shape("y-fork", 40000, y30);
  FitResult direct = fit_finer(shape, false);
  FitResult staged = fit_finer(shape, true);
  EXPECT_FALSE(direct.report.coarse_evolution.has_value());
  ASSERT_TRUE(staged.report.coarse_evolution.has_value());
  EXPECT_EQ(staged.report.initial_mesh.refinement_levels, 1);
  EXPECT_GE(staged.report.initial_mesh.levels_after_coarse_evolution, 1);

  MeshStatistics a = mesh_statistics(direct.mesh), b = mesh_statistics(staged.mesh);
  EXPECT_EQ(b.vertices, a.vertices);
  EXPECT_EQ(b.faces, a.faces);
  EXPECT_EQ(b.irregular_vertices, a.irregular_vertices);
  EXPECT_EQ(b.euler_characteristic, a.euler_characteristic);
  EXPECT_EQ(intersecting_face_pairs(staged.mesh).size(), 0u);

  double direct_p95 = cloud_to_mesh_relative_to_local_radius(direct.mesh, shape.cloud, shape.surface).p95;
  double staged_p95 = cloud_to_mesh_relative_to_local_radius(staged.mesh, shape.cloud, shape.surface).p95;
  EXPECT_LT(staged_p95, direct_p95);
  EXPECT_LE(staged_p95, 0.05) << "issue 6's coverage: 95 % of the cloud within 5 % of the local radius";
}

//! The paper's mode keeps the paper's single evolution at any resolution.
TEST(CoarseToFine, ThePapersModeEvolvesOnce) {
  GeneratedShape shape = test::small_shape("t-shape", 20000);
  FitOptions options;
  options.backend = BackendKind::kSerial;
  options.initial.target_vertices = 4000;
  options.evolution.mode = EvolutionParameters::Mode::kPaper;
  options.evolution.iterations = 2;
  FitResult paper = run_fit(FitInput{shape.cloud, shape.skeleton}, options);
  EXPECT_FALSE(paper.report.coarse_evolution.has_value());
  EXPECT_GE(paper.report.initial_mesh.refinement_levels, 2);
}

}  // namespace
}  // namespace mcquad
