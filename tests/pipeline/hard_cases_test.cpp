// Issue 6's hard cases in robust mode (the default): what holds on each,
// measured the way `mcquad metrics` does. docs/HARD_CASES.md has the full
// table beside the paper's mode, and what does not hold yet.
#include <gtest/gtest.h>

#include <algorithm>

#include "evolution/evolution_fixture.h"
#include "generate/true_surface_distance.h"
#include "mesh/face_intersections.h"
#include "mesh/quad_shape.h"
#include "metrics/mesh_metrics.h"
#include "pipeline/fit.h"

namespace mcquad {
namespace {

struct HardCase {
  const char* label;
  const char* shape;
  ShapeOptions options;
  //! Whether 95 % of the cloud lies within 5 % of the local radius plus
  //! 1.96 sigma of the mesh. Not on the 15-degree Y at the default
  //! resolution (docs/HARD_CASES.md says why); it is one level finer
  //! (Issue6.FifteenDegreeYIsCoveredOneLevelFiner).
  bool covered;
  //! The most of the area that may face against the true surface: issue
  //! 20's 0.1 %, but on the thin branch, which has turned 0.15 % since the
  //! rings keep their port's tilt (mesh/initial_mesh.cpp; 0.08 % before,
  //! while its mean and p95 distance to the true surface fell, 1.52 -> 1.15
  //! and 4.85 -> 3.61 % of r, docs/HARD_CASES.md, "Rings that keep their
  //! port's tilt"). It misses issue 20's bounds on those anyway.
  double inward_bound = 0.001;
};

//! gtest prints the case by its label rather than its bytes.
void PrintTo(const HardCase& c, std::ostream* os) { *os << c.label; }

ShapeOptions with(double angle = 60, double noise = 0, double outliers = 0, double density_ratio = 1, int holes = 0) {
  ShapeOptions o;
  o.angle_degrees = angle;
  o.noise = noise;
  o.outliers = outliers;
  o.density_ratio = density_ratio;
  o.holes = holes;
  return o;
}

const HardCase kCases[] = {
    {"y_fork_30", "y-fork", with(30), true},
    {"y_fork_15", "y-fork", with(15), false},
    {"tight_knot", "tight-knot", with(), true},
    {"parallel_tubes", "parallel-tubes", with(), true},
    {"thin_branch", "thin-branch", with(), true, 0.002},
    {"noise_2", "t-shape", with(60, 0.02), true},
    {"noise_5", "t-shape", with(60, 0.05), true},
    {"noise_10", "t-shape", with(60, 0.10), true},
    {"outliers", "t-shape", with(60, 0, 0.01), true},
    {"density_10", "t-shape", with(60, 0, 0, 10), true},
    {"holes", "t-shape", with(60, 0, 0, 1, 3), true},
};

struct Measured {
  size_t crossing = 0, folded = 0;
  double least_jacobian = 1, coverage_p95 = 0, surface_mean = 0, surface_p95 = 0, inward_area = 0;
};

Measured measure(const test::Fixture& f, const std::vector<float>& positions) {
  QuadMesh mesh = f.initial.mesh;
  set_positions(mesh, positions);
  Measured m;
  m.crossing = intersecting_face_pairs(mesh).size();
  m.folded = folded_edges(mesh);
  m.least_jacobian = measure_quad_shape(mesh).min_scaled_jacobian;
  m.coverage_p95 = cloud_to_mesh_relative_to_local_radius(mesh, f.shape.cloud, f.shape.surface).p95;
  TrueSurfaceDistance truth = measure_true_surface_distance(mesh, f.shape.surface);
  m.surface_mean = truth.relative.mean;
  m.surface_p95 = truth.relative.p95;
  m.inward_area = truth.inward_area_fraction;
  return m;
}

//! The backends every hard case runs on: the serial path, and OpenCL where
//! it is built (PoCL in CI, where a missing device fails).
const char* const kBackends[] = {"serial",
#ifdef MCQUAD_WITH_OPENCL
                                 "opencl"
#endif
};

//! Robust mode's fit on `backend` (the evolution and the smoothing of turned
//! faces after it); empty when OpenCL finds no
//! device (test::opencl_or_skip records a failure where CI requires one).
std::vector<float> evolve_robust(const test::Fixture& f, const std::string& backend) {
  if (backend == "serial") {
    SerialBackend serial;
    return f.fit_on(serial, EvolutionParameters::Mode::kRobust);
  }
#ifdef MCQUAD_WITH_OPENCL
  auto opencl = test::opencl_or_skip();
  if (!opencl) return {};
  return f.fit_on(*opencl, EvolutionParameters::Mode::kRobust);
#else
  return {};
#endif
}

class HardCases : public ::testing::TestWithParam<std::tuple<HardCase, const char*>> {};

//! No face pair crosses or folds that did not already in the initial mesh,
//! every quad keeps a scaled Jacobian of at least 0.3 (or what it started
//! with), the cloud is covered, no more than 0.1 % of the area faces against
//! the true surface, and under noise the mesh lies closer to the
//! true surface, on average, than the noise's sigma (the paper's step does
//! not at 5 % and 10 %: it settles on the shell's inner layer).
TEST_P(HardCases, RobustModeKeepsTheMeshValidAndCoversTheCloud) {
  const auto& [c, backend] = GetParam();
  test::Fixture f(c.shape, 40000, c.options);
  std::vector<float> positions = evolve_robust(f, backend);
  if (positions.empty()) GTEST_SKIP() << "no OpenCL device";
  Measured start = measure(f, f.arrays.positions);
  Measured end = measure(f, positions);
  EXPECT_LE(end.crossing, start.crossing);
  if (start.crossing == 0) {
    EXPECT_EQ(end.crossing, 0u);
  }
  EXPECT_LE(end.folded, start.folded);
  EXPECT_GE(end.least_jacobian, std::min(0.3, start.least_jacobian) - 1e-3);
  if (c.covered) {
    EXPECT_LE(end.coverage_p95, 0.05 + 1.96 * c.options.noise);
  }
  if (c.options.noise > 0) {
    EXPECT_LT(end.surface_mean, c.options.noise);
  }
  // Issue 20's bound. The T's creases with outliers and holes met it once
  // the junctions were inflated (0.50 and 0.31 % before), the 30-degree Y's
  // crotch once rays passed through the cells facing away (0.17 % before,
  // cells/cell_facing.h), the thin branch's once the turned faces were
  // smoothed after the evolution (0.77 % before, 0.08 % then,
  // evolution/turned_face_smoothing.h; HardCase::inward_bound has it now).
  EXPECT_LE(end.inward_area, c.inward_bound) << "share of the area facing against the true surface";
}

INSTANTIATE_TEST_SUITE_P(Issue6, HardCases,
                         ::testing::Combine(::testing::ValuesIn(kCases), ::testing::ValuesIn(kBackends)),
                         [](const auto& test_info) {
                           return std::string(std::get<0>(test_info.param).label) + "_" + std::get<1>(test_info.param);
                         });

//! Random trees of tubes (`random-tree`, one per seed: up to three junctions
//! of valence 3 to 6, random directions, radii and ends): robust mode's fit
//! adds no crossing pair or fold, keeps every quad's shape where the guard
//! keeps it, and covers the cloud (95 % within 5 % of the local radius).
//! Issue 20's other bounds do not hold on every tree yet (docs/HARD_CASES.md,
//! "Random trees").
class RandomTreeFits : public ::testing::TestWithParam<std::tuple<uint64_t, const char*>> {};

TEST_P(RandomTreeFits, NeverCrossAndCoverTheCloud) {
  const auto& [seed, backend] = GetParam();
  ShapeOptions options;
  options.seed = seed;
  test::Fixture f("random-tree", 20000, options);
  std::vector<float> positions = evolve_robust(f, backend);
  if (positions.empty()) GTEST_SKIP() << "no OpenCL device";
  Measured start = measure(f, f.arrays.positions);
  Measured end = measure(f, positions);
  EXPECT_EQ(start.crossing, 0u);
  EXPECT_EQ(end.crossing, 0u);
  EXPECT_LE(end.folded, start.folded);
  EXPECT_GE(end.least_jacobian, std::min(0.3, start.least_jacobian) - 1e-3);
  EXPECT_LE(end.coverage_p95, 0.05);
}

INSTANTIATE_TEST_SUITE_P(Issue20, RandomTreeFits,
                         ::testing::Combine(::testing::Range<uint64_t>(1, 7), ::testing::ValuesIn(kBackends)),
                         [](const auto& test_info) {
                           return "seed_" + std::to_string(std::get<0>(test_info.param)) + "_" +
                                  std::get<1>(test_info.param);
                         });

//! The fans of three limbs 30 and 40 degrees apart, each moved at once to
//! where its limbs part (spread_acute_junctions, skeleton/acute_junctions.h),
//! meet every bound of issue 20's fit on both backends, evolved alone. The
//! 30-degree fan's crease had sunk a tube radius into the trunk (mean
//! 1.23 %, p95 2.72 % of r before; docs/HARD_CASES.md, "A fan moves at
//! once"); the 40-degree fan moved pair by pair, its third limb's crease
//! left a mean of 0.59 % of r (0.15 % now; "Limbs that hug the forking
//! pair"). The 20-degree fan needs the whole fit (below).
class FanFits : public ::testing::TestWithParam<std::tuple<double, const char*>> {};

TEST_P(FanFits, MeetEveryBoundOfTheFit) {
  const auto& [angle, backend] = GetParam();
  test::Fixture f("fan", 40000, with(angle));
  std::vector<float> positions = evolve_robust(f, backend);
  if (positions.empty()) GTEST_SKIP() << "no OpenCL device";
  Measured end = measure(f, positions);
  EXPECT_EQ(end.crossing, 0u);
  EXPECT_LE(end.inward_area, 0.001);
  EXPECT_LE(end.surface_mean, 0.01);
  EXPECT_LE(end.surface_p95, 0.03);
  EXPECT_LE(end.coverage_p95, 0.05);
  EXPECT_GE(end.least_jacobian, 0.2);
}

INSTANTIATE_TEST_SUITE_P(Issue20, FanFits,
                         ::testing::Combine(::testing::Values(30.0, 40.0), ::testing::ValuesIn(kBackends)),
                         [](const auto& test_info) {
                           return "degrees_" + std::to_string(int(std::get<0>(test_info.param))) + "_" +
                                  std::get<1>(test_info.param);
                         });

//! A generated shape fitted as `mcquad fit` fits it, measured as
//! `scripts/junction-bounds` measures it.
struct WholeFit {
  const char* label;
  const char* shape;
  int points;
  ShapeOptions options;
};

void PrintTo(const WholeFit& c, std::ostream* os) { *os << c.label; }

ShapeOptions tree(uint64_t seed) {
  ShapeOptions o;
  o.seed = seed;
  return o;
}

//! Junction shapes fitted as `mcquad fit` fits them meet every bound of
//! issue 20's fit on both backends.
class WholeFits : public ::testing::TestWithParam<std::tuple<WholeFit, BackendKind>> {};

void expect_every_bound_of_the_fit(const WholeFit& c, BackendKind kind) {
  const GeneratedShape shape = test::small_shape(c.shape, c.points, c.options);
  FitOptions options;
  options.backend = kind;
  const FitResult fit = run_fit(FitInput{shape.cloud, shape.skeleton, "shape.ply", "shape.skeleton.obj"}, options);
  const TrueSurfaceDistance truth = measure_true_surface_distance(fit.mesh, shape.surface);
  EXPECT_EQ(intersecting_face_pairs(fit.mesh).size(), 0u);
  EXPECT_LE(truth.inward_area_fraction, 0.001);
  EXPECT_LE(truth.relative.mean, 0.01);
  EXPECT_LE(truth.relative.p95, 0.03);
  EXPECT_LE(cloud_to_mesh_relative_to_local_radius(fit.mesh, shape.cloud, shape.surface).p95, 0.05);
  EXPECT_GE(measure_quad_shape(fit.mesh).min_scaled_jacobian, 0.2);
}

TEST_P(WholeFits, MeetEveryBoundOfTheFit) {
  const auto& [c, kind] = GetParam();
  REQUIRE_BACKEND(device_found, kind);
  expect_every_bound_of_the_fit(c, kind);
}

const WholeFit kWholeFits[] = {
    // Shapes whose third limb hugs a forking pair (hugging_limbs,
    // skeleton/acute_junctions.h): the 20-degree fan, and random tree 10's
    // trunk with a branch folded back along it on either side. Moved pair by
    // pair, the third limb's crease stayed a double wall inside the cloud
    // (inward area 0.175 and 0.206 %, over issue 20's 0.1 %); the 20-degree
    // fan's stem needs the refinement where the evolution left the cloud
    // uncovered (coverage 8.3 % of r evolved alone, 2.2 % fitted).
    {"fan_20", "fan", 40000, with(20)},
    {"random_tree_10", "random-tree", 30000, tree(10)},
    // Fat limbs crowding a junction of valence 5 or 6, with an acute pair
    // whose fork would stand less than kLeastStemInRadii of the pair's wider
    // radius from the junction it leaves. Moved, the fork's block overlapped
    // the junction's (21 and 34 crossing face pairs among the blocks), and
    // the fit left a slot through the fat limb (inward area 0.82 and 0.34 %,
    // mean 1.57 and 2.06 % of r); now the pair stays on the junction's block.
    {"random_tree_30", "random-tree", 30000, tree(30)},
    {"random_tree_33", "random-tree", 30000, tree(33)},
    // Six fat limbs round a junction 24.7 degrees off a cube's faces: with
    // the cube block, which it took until 2026-12-07, the fit kept two fat
    // limbs' walls pressed together inside the body (inward area 0.41 %,
    // mean 1.00 % of r); now only a junction within 10 degrees of a cube
    // gets one (kCubeFitDegrees, mesh/initial_mesh.cpp).
    {"random_tree_34", "random-tree", 30000, tree(34)},
};

INSTANTIATE_TEST_SUITE_P(Issue20, WholeFits,
                         ::testing::Combine(::testing::ValuesIn(kWholeFits),
                                            ::testing::ValuesIn(test::backend_kinds())),
                         test::case_and_backend_label<WholeFit>);

//! Random trees whose fit still misses issue 20's bounds, kept so that they
//! are run and looked at (serial; `--gtest_also_run_disabled_tests
//! --gtest_filter='*KnownHardRandomTree*'`). Each turns its faces near a
//! junction of five or six fat bones, where its initial mesh already turned
//! faces against the true surface (docs/HARD_CASES.md, 2026-12-07, on
//! junctions of five and six bones and the cube). As this test measures
//! them on 2026-12-07: tree 29 turns 0.245 % of its area inward; tree 2
//! 0.195 %, mean 1.14 % of r; tree 17 0.116 %, mean 1.34 % and p95 4.26 %.
class KnownHardRandomTreeFits : public ::testing::TestWithParam<WholeFit> {};

TEST_P(KnownHardRandomTreeFits, DISABLED_MeetEveryBoundOfTheFit) {
  expect_every_bound_of_the_fit(GetParam(), BackendKind::kSerial);
}

const WholeFit kKnownHardTrees[] = {
    {"random_tree_29", "random-tree", 30000, tree(29)},
    {"random_tree_2", "random-tree", 30000, tree(2)},
    {"random_tree_17", "random-tree", 30000, tree(17)},
};

INSTANTIATE_TEST_SUITE_P(Issue20, KnownHardRandomTreeFits, ::testing::ValuesIn(kKnownHardTrees),
                         [](const auto& test_info) { return std::string(test_info.param.label); });

//! The 15-degree Y's branches never part and are built as one tube, twice as
//! wide at its end as the trunk's: 16 vertices around do not resolve the two
//! branch tips beside the notch between them (coverage 9.3 % of r). One
//! refinement level more does, and the mesh stays valid.
TEST(Issue6, FifteenDegreeYIsCoveredOneLevelFiner) {
  InitialMeshOptions finer;
  finer.target_vertices = 2000;
  test::Fixture f("y-fork", 40000, with(15), finer);
  ASSERT_GT(f.arrays.positions.size() / 3, 2000u);
  Measured start = measure(f, f.arrays.positions);
  EXPECT_EQ(start.crossing, 0u);
  for (const char* backend : kBackends) {
    std::vector<float> positions = evolve_robust(f, backend);
    if (positions.empty()) continue;  // no OpenCL device: recorded by opencl_or_skip where required
    Measured end = measure(f, positions);
    EXPECT_EQ(end.crossing, 0u) << backend;
    EXPECT_EQ(end.folded, 0u) << backend;
    EXPECT_GE(end.least_jacobian, std::min(0.3, start.least_jacobian) - 1e-3) << backend;
    EXPECT_LE(end.coverage_p95, 0.05) << backend;
  }
}

#ifdef MCQUAD_WITH_OPENCL
//! The guard, the skeleton regions and the rays' bands run the same on the
//! device: robust mode on hard cases gives the serial path's mesh (on the
//! thin branch with the local epsilon too, and at 10 % noise, where the
//! bands gather most cells).
TEST(OpenCLParity, RobustModeOnHardCasesMatchesTheSerialPath) {
  REQUIRE_OPENCL(opencl);
  for (const HardCase& c : {kCases[0], kCases[4], kCases[7]}) {
    test::Fixture f(c.shape, 30000, c.options);
    f.parameters.local_epsilon = std::string(c.shape) == "thin-branch";
    SerialBackend serial;
    serial.load(f.cells, f.arrays, f.regions);
    opencl->load(f.cells, f.arrays, f.regions);
    std::vector<float> a = evolve(serial, f.arrays, f.parameters).positions;
    std::vector<float> b = evolve(*opencl, f.arrays, f.parameters).positions;
    EXPECT_LE(test::count_differing(a, b, 1e-3f * float(f.radius)), a.size() / 3 / 50) << c.label;
    EXPECT_EQ(measure(f, b).crossing, measure(f, a).crossing) << c.label;
  }
}
#endif

}  // namespace
}  // namespace mcquad
