// Robust mode's reach for the cloud the evolution leaves uncovered
// (evolution/uncovered_reach.h): alone on a mesh left inside its cloud and
// on meshes with nothing to reach, and through the whole fit as a user runs
// it on issue 14's stand-in with a fat body, measured against the true
// surface.
#include <gtest/gtest.h>
#include <omp.h>

#include "evolution/evolution_fixture.h"
#include "evolution/uncovered_reach.h"
#include "generate/true_surface_distance.h"
#include "mesh/face_intersections.h"
#include "mesh/folds.h"
#include "metrics/surface_distance.h"

namespace mcquad {
namespace {

//! The initial mesh lies at 0.7 of the radius, 0.3 r inside the cloud
//! everywhere: the pull brings it out toward the cloud (the share of the
//! cloud farther than the distance falls by more than half, and so does the
//! mesh's mean distance to the true surface), and nothing crosses or folds
//! on the way.
TEST(UncoveredReach, PullsAMeshLeftInsideItsCloudOutToIt) {
  test::Fixture f("t-shape", 20000);
  QuadMesh mesh = f.initial.mesh;
  const double distance = kReachDistance * f.parameters.epsilon;
  const double before = measure_true_surface_distance(mesh, f.shape.surface).relative.mean;
  ASSERT_GT(before, 0.2) << "a mesh already on the cloud proves nothing";
  UncoveredReach reach = pull_toward_uncovered_cloud(mesh, f.arrays, f.shape.cloud, distance,
                                                     kReachLongestStep * f.parameters.epsilon, 16);
  EXPECT_GT(reach.rounds, 0);
  EXPECT_GT(reach.uncovered_before, f.shape.cloud.size() / 2);
  EXPECT_LT(reach.uncovered_after, reach.uncovered_before / 2);
  EXPECT_LT(measure_true_surface_distance(mesh, f.shape.surface).relative.mean, before / 2);
  EXPECT_EQ(intersecting_face_pairs(mesh).size(), 0u);
  EXPECT_EQ(folded_edges(mesh), 0u);
}

//! The same pull, to the last bit, on one thread and on several: the order
//! the pulls are summed in must not follow how the threads split the cloud
//! (a user's fit would otherwise change with the machine it runs on; the
//! kitten's did at 16 threads). The per-thread sums merged before agreed on
//! this shape too: the fault was which of two equally near triangles a
//! point found, TriangleTree's test, where such ties are certain.
TEST(UncoveredReach, PullsTheSameWhateverTheThreadCount) {
  test::Fixture f("t-shape", 20000);
  const int threads = omp_get_max_threads();
  std::vector<std::vector<float>> positions;
  for (int count : {1, 4, 16}) {
    omp_set_num_threads(count);
    QuadMesh mesh = f.initial.mesh;
    pull_toward_uncovered_cloud(mesh, f.arrays, f.shape.cloud, kReachDistance * f.parameters.epsilon,
                                kReachLongestStep * f.parameters.epsilon, 16);
    positions.push_back(mesh_positions(mesh));
  }
  omp_set_num_threads(threads);
  ASSERT_NE(positions[0], mesh_positions(f.initial.mesh)) << "nothing pulled proves nothing";
  for (size_t k = 1; k < positions.size(); ++k) EXPECT_EQ(positions[k], positions[0]) << "run " << k;
}

//! The cloud made of the mesh's own vertices and face centres, with three
//! stray points far off it: nothing is uncovered but the strays, too few
//! to pull any vertex, so the mesh stays as it is.
TEST(UncoveredReach, LeavesACoveredMeshAloneWhateverAFewStrayPointsSay) {
  test::Fixture f("t-shape", 20000);
  const QuadMesh& mesh = f.initial.mesh;
  PointCloud cloud;
  for (auto v : mesh.vertices()) cloud.points.push_back(point_of(mesh, v).cast<float>());
  for (auto face : mesh.faces()) {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (auto v : mesh.fv_range(face)) centre += point_of(mesh, v) / 4.0;
    cloud.points.push_back(centre.cast<float>());
  }
  for (int k = 0; k < 3; ++k) cloud.points.push_back(Eigen::Vector3f(10.0f + float(k), 10.0f, 10.0f));
  QuadMesh pulled = mesh;
  UncoveredReach reach = pull_toward_uncovered_cloud(pulled, f.arrays, cloud, 0.05 * f.radius, f.radius, 16);
  EXPECT_EQ(reach.rounds, 0);
  EXPECT_EQ(reach.uncovered_before, 3u);
  EXPECT_EQ(mesh_positions(pulled), mesh_positions(mesh));
}

struct Fitted {
  FitResult fit;
  TrueSurfaceDistance truth;
  double coverage = 0;  //!< cloud -> mesh 95th percentile, in local radii
};

Fitted fit(const GeneratedShape& shape, BackendKind backend, bool reach_uncovered) {
  FitOptions options;
  options.backend = backend;
  options.evolution.reach_uncovered = reach_uncovered;
  Fitted f{run_fit(FitInput{shape.cloud, shape.skeleton, "shape.ply", "shape.skeleton.obj"}, options), {}, 0};
  f.truth = measure_true_surface_distance(f.fit.mesh, shape.surface);
  f.coverage = cloud_to_mesh_relative_to_local_radius(f.fit.mesh, shape.cloud, shape.surface).p95;
  return f;
}

class ReachInTheFit : public ::testing::TestWithParam<BackendKind> {};

//! Whether either evolution of the fit (the coarse one, when there was one) kept its reach.
bool reach_kept(const FitReport& report) {
  for (const auto* evolution : {&report.coarse_evolution, &report.evolution})
    if (*evolution && (*evolution)->uncovered_reach && (*evolution)->uncovered_reach->kept) return true;
  return false;
}

//! The cloud -> mesh 95th percentile over the whole cloud: the verdict's coverage.
double verdict_coverage(const Fitted& f, const GeneratedShape& shape) {
  return summarize_distances(cloud_to_mesh_distances(f.fit.mesh, shape.cloud)).p95;
}

//! Issue 14's "reach the whole cloud where the body is not a tube", on its
//! stand-in with a fat body (blob-limbs: thin legs under a body of radius
//! 2.5, a neck, a tail and an ear with no bone), seeds 1 to 4. The default
//! fit leaves the cloud round the legs' roots under the body uncovered
//! (cloud -> mesh p95 0.29 to 0.34 of the local radius). The reached fit is
//! kept or refused as a whole (by the area it turns against the scan and by
//! its coverage), so per seed: kept, it covers the cloud better as the
//! verdict measures it; refused, the fit is the one without, vertex for
//! vertex. At least one seed keeps it. On every seed nothing crosses or
//! folds and at most 0.5 % of the area faces against the true surface.
//! Against the true surface the kept fits are not all better: on the
//! serial backend seeds 2 and 3 halve their coverage relative to the local
//! radius (0.294 -> 0.138 and 0.321 -> 0.170), but OpenCL's seed 2 keeps a
//! fit whose coverage so measured is worse (0.294 -> 0.311: its thin legs
//! lose what its body gains; docs/DESIGN.md, a known defect of the choice).
//! (The ear it does not grow: docs/DESIGN.md.)
TEST_P(ReachInTheFit, CoversMoreOfAFatBodysCloudWhereKept) {
  REQUIRE_BACKEND(device_found, GetParam());
  int kept = 0;
  for (uint64_t seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    ShapeOptions options;
    options.seed = seed;
    GeneratedShape shape = test::small_shape("blob-limbs", 40000, options);
    Fitted off = fit(shape, GetParam(), false);
    Fitted on = fit(shape, GetParam(), true);
    EXPECT_FALSE(off.fit.report.evolution->uncovered_reach.has_value());
    ASSERT_TRUE(on.fit.report.evolution->uncovered_reach.has_value());
    EXPECT_GT(off.coverage, 0.2) << "a fit with nothing to reach proves nothing";
    EXPECT_EQ(intersecting_face_pairs(on.fit.mesh).size(), 0u);
    EXPECT_EQ(folded_edges(on.fit.mesh), 0u);
    EXPECT_LE(on.truth.inward_area_fraction, 0.005);
    if (reach_kept(on.fit.report)) {
      ++kept;
      EXPECT_LT(verdict_coverage(on, shape), verdict_coverage(off, shape));
    } else {
      EXPECT_EQ(mesh_positions(on.fit.mesh), mesh_positions(off.fit.mesh));
    }
    std::printf("blob-limbs seed %d, %s: reach %s, coverage %.4f -> %.4f, true-surface mean %.4f -> %.4f\n", int(seed),
                GetParam() == BackendKind::kSerial ? "serial" : "opencl",
                reach_kept(on.fit.report) ? "kept" : "refused", off.coverage, on.coverage, off.truth.relative.mean,
                on.truth.relative.mean);
  }
  EXPECT_GE(kept, 1);
}

INSTANTIATE_TEST_SUITE_P(Issue14, ReachInTheFit, ::testing::ValuesIn(test::backend_kinds()), test::backend_label);

}  // namespace
}  // namespace mcquad
