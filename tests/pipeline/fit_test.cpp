// The whole fit (run_fit), from memory and from files, on generated shapes.
#include <gtest/gtest.h>

#include <algorithm>

#include "core/errors.h"
#include "evolution/evolution_fixture.h"
#include "generate/shapes.h"
#include "generate/true_surface_distance.h"
#include "mesh/face_intersections.h"
#include "mesh/quad_shape.h"
#include "metrics/mesh_statistics.h"
#include "pipeline/fit.h"
#include "skeleton/cloud_skeleton.h"

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

//! A refined fit evolves without feeding back its own noise: where the mesh
//! is about as dense as the cloud (a T of 5,000 points, 3,153 vertices),
//! the current mesh's curvature, fitted over edges shorter than the cells'
//! samples spread, made each step rougher than the last (the error level
//! rose 0.0103 -> 0.0149 over the refined evolution, the true-surface mean
//! 1.08 % r). The curvature of the mesh it started from keeps it still.
class RefinedEvolution : public ::testing::TestWithParam<BackendKind> {};

TEST_P(RefinedEvolution, DoesNotFeedBackItsOwnNoise) {
  GeneratedShape shape = test::small_shape("t-shape", 5000);
  FitOptions options;
  options.backend = GetParam();
  options.initial.target_vertices = 2400;
  FitResult fit = run_fit(FitInput{shape.cloud, shape.skeleton}, options);
  ASSERT_TRUE(fit.report.coarse_evolution.has_value());
  const auto& iterations = fit.report.evolution->iterations;
  ASSERT_FALSE(iterations.empty());
  EXPECT_LE(iterations.back().error_level, iterations.front().error_level);
  TrueSurfaceDistance truth = measure_true_surface_distance(fit.mesh, shape.surface);
  EXPECT_LE(truth.relative.mean, 0.006) << "0.33 % r now, 1.08 % r with the current mesh's curvature";
  EXPECT_LE(truth.relative.p95, 0.015);
}

INSTANTIATE_TEST_SUITE_P(CoarseToFine, RefinedEvolution, ::testing::ValuesIn(test::backend_kinds()),
                         test::backend_label);

//! A tube sampled sparsely for its radius: 800 points over a capped tube of
//! radius 1 and length 8, 0.28 r between neighbours, as on the octopus's
//! arms. Randomly sampled, the cloud has gaps, and a kd-tree leaf of two
//! points on either side of one reached a third of the way round the arm;
//! a vertex inside its box averaged the chord and stayed inside. Leaves are
//! split where longer than half the tube's radius (host/pipeline/prepare.cpp);
//! without that the fit's mean / p95 were 2.63 / 9.55 % r on both backends.
//! Issue 20's bounds (1 / 3 % r) are not met yet: the bounds below hold
//! the gain.
class SparseCloud : public ::testing::TestWithParam<BackendKind> {};

TEST_P(SparseCloud, AThinTubeIsNotDentedWhereItsPointsLeaveGaps) {
  GeneratedShape shape = test::small_shape("tube", 800);
  FitOptions options;
  options.backend = GetParam();
  FitResult fit = run_fit(FitInput{shape.cloud, shape.skeleton}, options);
  TrueSurfaceDistance truth = measure_true_surface_distance(fit.mesh, shape.surface);
  EXPECT_LE(truth.relative.mean, 0.018) << "1.33 % r now, 2.63 % r without the rule";
  EXPECT_LE(truth.relative.p95, 0.06) << "4.22 % r now, 9.55 % r without the rule";
  EXPECT_EQ(intersecting_face_pairs(fit.mesh).size(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Issue20, SparseCloud, ::testing::ValuesIn(test::backend_kinds()), test::backend_label);

//! Thin branches: a fifth and a quarter of their trunk's radius at 60
//! degrees, a fifth at 45, 0.3 and a quarter at 50. A branch's first bone
//! measures the trunk, so its block's face is as wide as the trunk's and,
//! the junction kept at the start fraction, lies inside it; the branch's
//! tube narrowed from that face in one ring, a funnel whose upper half faced
//! up the trunk's inside and stayed a pocket (without limb ports, mean / p95
//! 1.07 / 3.13, 1.15 / 3.96, 1.91 / 3.90, 6.06 / 34.16 and 2.44 / 14.78 %
//! r). With limb ports (the default) a port of the branch's size is inset
//! in that face, lifted to the trunk's wall and turned across the bone
//! (mesh/inset_port.h): the fit meets every bound of issue 20 on both
//! backends. In the face's plane the inset made the fifth at 60 degrees
//! worse (1.37 / 5.55 % r) and folded the one at 45 into a plug; lifted but
//! in the face's plane, the quarter at 50 kept 1.67 / 2.89 and 0.13 %
//! inward.
class ThinBranch : public ::testing::TestWithParam<std::tuple<BackendKind, std::tuple<double, double>>> {};

TEST_P(ThinBranch, MeetsEveryBoundOfTheFitWithLimbPorts) {
  ShapeOptions shape_options;
  std::tie(shape_options.branch_radius, shape_options.angle_degrees) = std::get<1>(GetParam());
  GeneratedShape shape = test::small_shape("thin-branch", 40000, shape_options);
  double p95_without = 0;
  for (bool limb_ports : {false, true}) {
    FitOptions options;
    options.backend = std::get<0>(GetParam());
    options.initial.limb_ports = limb_ports;
    FitResult fit = run_fit(FitInput{shape.cloud, shape.skeleton}, options);
    TrueSurfaceDistance truth = measure_true_surface_distance(fit.mesh, shape.surface);
    if (!limb_ports) {
      p95_without = truth.relative.p95;
      continue;
    }
    EXPECT_LE(truth.inward_area_fraction, 0.001);
    EXPECT_LE(truth.relative.mean, 0.01);
    EXPECT_LE(truth.relative.p95, 0.03);
    // The case proves something only where the ports make the difference.
    EXPECT_LT(truth.relative.p95, 0.8 * p95_without) << "p95 without limb ports " << p95_without;
    EXPECT_LE(cloud_to_mesh_relative_to_local_radius(fit.mesh, shape.cloud, shape.surface).p95, 0.05);
    EXPECT_GE(measure_quad_shape(fit.mesh).min_scaled_jacobian, 0.2);
    EXPECT_EQ(intersecting_face_pairs(fit.mesh).size(), 0u);
  }
}

//! Kept while it fails (docs/HARD_CASES.md, "Thin limbs start at their
//! trunk's wall"): a branch at 50 degrees, 0.15 of its trunk's radius. Its
//! port is inset, lifted and turned across the bone, but the fit still
//! stands off the true surface below the branch's root (mean / p95 1.9 /
//! 4.8 % r; 3.6 / 14.8 with the ring in the face's plane).
TEST(KnownHardThinBranch, DISABLED_At50DegreesMeetsEveryBoundOfTheFit) {
  ShapeOptions shape_options;
  shape_options.branch_radius = 0.15;
  shape_options.angle_degrees = 50;
  GeneratedShape shape = test::small_shape("thin-branch", 40000, shape_options);
  FitOptions options;
  options.backend = BackendKind::kSerial;
  FitResult fit = run_fit(FitInput{shape.cloud, shape.skeleton}, options);
  TrueSurfaceDistance truth = measure_true_surface_distance(fit.mesh, shape.surface);
  EXPECT_LE(truth.inward_area_fraction, 0.001);
  EXPECT_LE(truth.relative.mean, 0.01);
  EXPECT_LE(truth.relative.p95, 0.03);
}

INSTANTIATE_TEST_SUITE_P(Issue20, ThinBranch,
                         ::testing::Combine(::testing::ValuesIn(test::backend_kinds()),
                                            ::testing::Values(std::make_tuple(0.2, 60.0), std::make_tuple(0.25, 60.0),
                                                              std::make_tuple(0.2, 45.0), std::make_tuple(0.3, 50.0),
                                                              std::make_tuple(0.25, 50.0))),
                         [](const auto& test_info) {
                           const BackendKind backend = std::get<0>(test_info.param);
                           const double radius = std::get<0>(std::get<1>(test_info.param));
                           const double angle = std::get<1>(std::get<1>(test_info.param));
                           return std::string(backend == BackendKind::kSerial ? "Serial" : "OpenCL") + "_radius" +
                                  std::to_string(int(std::lround(100 * radius))) + "_at" +
                                  std::to_string(int(std::lround(angle)));
                         });

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

//! The paper's mode starts from the paper's blocks: at the start fraction,
//! edge vertices midway; robust mode grows them and turns acute edges
//! toward their crotch (docs/CONSTRUCTION.md, section 3).
TEST(PapersMode, BuildsThePapersJunctionBlocks) {
  FitOptions options;
  EXPECT_EQ(effective_initial_options(options).block_edges, BlockEdges::kAcuteToCrotch);
  EXPECT_GT(effective_initial_options(options).block_fraction, options.initial.start_fraction);
  options.evolution.mode = EvolutionParameters::Mode::kPaper;
  EXPECT_EQ(effective_initial_options(options).block_edges, BlockEdges::kMidway);
  EXPECT_EQ(effective_initial_options(options).block_fraction, options.initial.start_fraction);
}

//! A robust fit at the default resolution on `kind`, or nothing where
//! OpenCL has no device (a failure where CI requires one).
std::optional<FitResult> fit_default(const GeneratedShape& shape, BackendKind kind, bool refine_uncovered) {
  FitOptions options;
  options.backend = kind;
  options.evolution.refine_uncovered = refine_uncovered;
  try {
    return run_fit(FitInput{shape.cloud, shape.skeleton, "shape.ply", "shape.skeleton.obj"}, options);
  } catch (const DeviceError& e) {
    if (test::opencl_required()) ADD_FAILURE() << e.what();
    return std::nullopt;
  }
}

//! The default fit with the refinement for coverage off, then on; nothing
//! where OpenCL has no device.
struct FitsBothWays {
  FitResult plain, refined;
};
std::optional<FitsBothWays> fit_both_ways(const GeneratedShape& shape, BackendKind kind) {
  auto plain = fit_default(shape, kind, false);
  auto refined = fit_default(shape, kind, true);
  if (!plain || !refined) return std::nullopt;
  return FitsBothWays{std::move(*plain), std::move(*refined)};
}

const VerdictCheck& uncovered_check(const FitResult& fit) {
  const VerdictCheck* check = fit.report.verdict->find("uncovered_cloud");
  EXPECT_NE(check, nullptr);
  return *check;
}

class CoverageRefinement : public testing::TestWithParam<BackendKind> {};

//! The 15-degree Y's merged stem is twice the trunk's width at its end, and
//! 16 vertices round the median tube leave the branch tips beside its notch
//! uncovered (the verdict's figure about twice its bound). At the default
//! resolution the fit then refines once and evolves again, and keeps the
//! finer fit: covered, valid, every check at least as good.
TEST_P(CoverageRefinement, AFitLeftUncoveredIsRefinedOnceAndCovers) {
  ShapeOptions y15;
  y15.angle_degrees = 15;
  auto fits = fit_both_ways(test::small_shape("y-fork", 40000, y15), GetParam());
  if (!fits) return;
  const FitResult* plain = &fits->plain;
  const FitResult* refined = &fits->refined;
  EXPECT_FALSE(uncovered_check(*plain).passed);
  ASSERT_TRUE(refined->report.coverage_refinement.has_value());
  const auto& coverage = *refined->report.coverage_refinement;
  EXPECT_TRUE(coverage.refined);
  EXPECT_TRUE(coverage.kept);
  EXPECT_DOUBLE_EQ(coverage.uncovered_at_default, uncovered_check(*plain).value);
  EXPECT_TRUE(uncovered_check(*refined).passed);
  EXPECT_TRUE(refined->report.verdict->passed);
  ASSERT_TRUE(refined->report.coarse_evolution.has_value());
  EXPECT_EQ(refined->report.initial_mesh.levels_after_coarse_evolution, 1);
  EXPECT_EQ(mesh_statistics(refined->mesh).faces, 4 * mesh_statistics(plain->mesh).faces);
  EXPECT_EQ(intersecting_face_pairs(refined->mesh).size(), 0u);
  for (const VerdictCheck& before : plain->report.verdict->checks) {
    if (before.passed) {
      EXPECT_TRUE(refined->report.verdict->find(before.name)->passed) << before.name;
    }
  }
}

//! A fit the verdict finds covered stays at the default resolution, and so
//! does one uncovered by more than one level can make up (a fat body's
//! short limbs, half a radius uncovered). What was decided is in the report.
TEST_P(CoverageRefinement, KeepsTheDefaultFitWhereRefiningCannotHelp) {
  auto covered = fit_default(test::small_shape("t-shape", 20000), GetParam(), true);
  auto far = fit_default(test::small_shape("stubby-limbs", 40000), GetParam(), true);
  if (!covered || !far) return;
  ASSERT_TRUE(covered->report.coverage_refinement.has_value());
  EXPECT_TRUE(uncovered_check(*covered).passed);
  EXPECT_FALSE(covered->report.coverage_refinement->refined);
  EXPECT_FALSE(covered->report.coarse_evolution.has_value());
  ASSERT_TRUE(far->report.coverage_refinement.has_value());
  EXPECT_GT(uncovered_check(*far).value, 4 * uncovered_check(*far).threshold);
  EXPECT_FALSE(far->report.coverage_refinement->refined);
  EXPECT_EQ(far->report.initial_mesh.levels_after_coarse_evolution, 0);
}

//! The tail loop at 20,000 points: one level finer covers the cloud better
//! (the verdict's figure 0.090 -> 0.051 of the median radius) but crosses
//! more face pairs, a check the default fit already fails. The default fit
//! is the result, the same mesh as without the refinement, and the report
//! says why. (Its case was the planar star of 8 at 30,000 points until the
//! blocks' crotches were searched in the cloud, then at 20,000 points until
//! crowded block corners were split, then random tree 17 at 20,000 points
//! until cells longer than half their tube's radius were split, and at
//! 15,000 until forks too near a junction they leave stayed: each time the
//! fit came to pass the check, or the finer fit every check the default fit
//! passes.)
TEST_P(CoverageRefinement, KeepsTheDefaultFitWhereTheRefinedOneIsWorseElsewhere) {
  auto fits = fit_both_ways(test::small_shape("tail-loop", 20000), GetParam());
  if (!fits) return;
  const FitResult* plain = &fits->plain;
  const FitResult* tried = &fits->refined;
  ASSERT_TRUE(tried->report.coverage_refinement.has_value());
  const auto& coverage = *tried->report.coverage_refinement;
  EXPECT_TRUE(coverage.refined);
  EXPECT_LT(coverage.uncovered_refined, coverage.uncovered_at_default);
  EXPECT_FALSE(coverage.kept);
  EXPECT_NE(std::find(coverage.worse.begin(), coverage.worse.end(), "intersecting_face_pairs"), coverage.worse.end());
  EXPECT_FALSE(tried->report.coarse_evolution.has_value());
  EXPECT_EQ(mesh_positions(tried->mesh), mesh_positions(plain->mesh));
  EXPECT_EQ(uncovered_check(*tried).value, uncovered_check(*plain).value);
}

INSTANTIATE_TEST_SUITE_P(Issue14, CoverageRefinement, testing::ValuesIn(test::backend_kinds()), test::backend_label);

//! A resolution the user asks for is the one the fit gives: no refinement
//! for coverage, nothing judged.
TEST(AskedResolution, IsNotRefinedForCoverage) {
  ShapeOptions y15;
  y15.angle_degrees = 15;
  GeneratedShape shape = test::small_shape("y-fork", 40000, y15);
  FitOptions options;
  options.backend = BackendKind::kSerial;
  options.initial.target_vertices = 500;
  FitResult fit = run_fit(FitInput{shape.cloud, shape.skeleton}, options);
  EXPECT_FALSE(fit.report.coverage_refinement.has_value());
  EXPECT_FALSE(fit.report.coarse_evolution.has_value());
}

//! Seed 8 of the fat body with thin limbs: the skeleton extracted from its
//! cloud has a limb whose tube overlaps another's where both leave the body,
//! and the initial mesh on it is no manifold. The fit without a skeleton
//! leaves that limb out and fits the rest, judged by the verdict (which the
//! part of the cloud not reached fails), and says which limb it was. The
//! same skeleton given by the user is refused: theirs is never changed.
//! (Seed 4 was the case until the rings kept their port's tilt
//! (docs/CONSTRUCTION.md, section 4): its whole skeleton now builds. Of
//! seeds 1-30, only 8 drops a limb now.)
TEST(FitWithoutSkeleton, LeavesOutALimbWhoseTubeOverlapsAnother) {
  ShapeOptions seed8;
  seed8.seed = 8;
  GeneratedShape shape = test::small_shape("blob-limbs", 40000, seed8);
  FitOptions options;
  options.backend = BackendKind::kSerial;
  FitResult fit = run_fit(FitInput{shape.cloud, {}, "blob-limbs.ply", ""}, options);
  ASSERT_TRUE(fit.report.skeleton_extraction.has_value());
  ASSERT_EQ(fit.report.skeleton_extraction->dropped_limbs.size(), 1u);
  ASSERT_TRUE(fit.extracted_skeleton.has_value());
  MeshStatistics s = mesh_statistics(fit.mesh);
  EXPECT_EQ(s.quads, s.faces);
  // One sheet round the tree, open where the limbs it kept end open (seed 8's
  // one open limb is the one left out).
  EXPECT_LE(s.boundary_loops, size_t(shape.open_ends));
  EXPECT_EQ(s.euler_characteristic, 2 - long(s.boundary_loops));
  EXPECT_EQ(intersecting_face_pairs(fit.mesh).size(), 0u);
  ASSERT_TRUE(fit.report.verdict.has_value());
  EXPECT_FALSE(fit.report.verdict->passed);

  ExtractedSkeleton extracted = extract_skeleton(shape.cloud, "blob-limbs.ply");
  EXPECT_EQ(extracted.skeleton.nodes.size(), fit.extracted_skeleton->nodes.size() + 1);
  EXPECT_THROW(run_fit(FitInput{shape.cloud, extracted.skeleton, "blob-limbs.ply", "mine.obj"}, options), OverlapError);
}

//! Random tree 10 at 30,000 points, from files as `mcquad init` reads them,
//! kept a quad at 0.10 until the initial mesh was built again with the
//! quads straightened before the junctions' inflation (mesh/initial_mesh.cpp,
//! refined): the inflation's guard had held the poor quad where the
//! refinement left it. With the straightened mesh: 0.31.
TEST(InitialMeshFromFiles, RandomTreeTenKeepsItsQuadsAbove0_2) {
  test::TempDir dir;
  ShapeOptions tree;
  tree.seed = 10;
  write_generated_shape(test::small_shape("random-tree", 30000, tree), dir.file("tree"));
  FitOptions options;
  options.evolve = false;
  FitResult result = run_fit(dir.file("tree/random-tree.ply"), dir.file("tree/random-tree.skeleton.obj"), options);
  EXPECT_GE(measure_quad_shape(result.mesh).min_scaled_jacobian, 0.2);
  EXPECT_EQ(intersecting_face_pairs(result.mesh).size(), 0u);
}

}  // namespace
}  // namespace mcquad
