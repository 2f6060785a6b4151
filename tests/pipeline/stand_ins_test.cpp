// Issue 14's stand-ins for real scans' skeletons and bodies, generated:
// a fat body with junctions deep inside it, thin legs and a limb with no
// bone (blob-limbs); skeletons moved off-centre by half a radius; end nodes
// a radius short of the tip. What holds on each is asserted; the issue's
// bounds that do not hold yet are measured in docs/REAL_DATA.md.
#include <gtest/gtest.h>

#include <algorithm>

#include "evolution/evolution_fixture.h"
#include "generate/true_surface_distance.h"
#include "mesh/face_intersections.h"
#include "metrics/mesh_metrics.h"

namespace mcquad {
namespace {

struct StandIn {
  const char* label;
  const char* shape;
  double skeleton_offset;
  double short_ends;
  //! Which of issue 14's bounds hold on it today (docs/REAL_DATA.md has the figures).
  bool faces_out;  //!< at most 0.5 % of the area faces against the true surface
  bool covered;    //!< cloud -> mesh 95th percentile at most 5 % of the local radius
  bool close;      //!< mesh -> true surface at most 2 % of the local radius on average
};

void PrintTo(const StandIn& c, std::ostream* os) { *os << c.label; }

const StandIn kStandIns[] = {
    {"blob_limbs", "blob-limbs", 0, 0, true, false, false},
    {"t_off_centre", "t-shape", 0.5, 0, true, true, true},
    {"t_short_ends", "t-shape", 0, 1, true, true, true},
    {"octopus_off_centre_short", "octopus", 0.5, 1, false, false, false},
};

class StandIns : public ::testing::TestWithParam<std::tuple<StandIn, BackendKind>> {};

//! The mesh stays valid (all quads, the skeleton's Euler characteristic, no
//! face pair crossing, no new fold) on every stand-in, and meets the bounds
//! of issue 14 that hold on it.
TEST_P(StandIns, FitStaysValidAndMeetsTheBoundsThatHold) {
  const auto& [c, kind] = GetParam();
  ShapeOptions options;
  options.skeleton_offset = c.skeleton_offset;
  options.short_ends = c.short_ends;
  test::Fixture f(c.shape, 40000, options);
  REQUIRE_BACKEND(backend, kind);
  std::vector<float> positions = f.fit_on(*backend, EvolutionParameters::Mode::kRobust);
  QuadMesh mesh = f.initial.mesh;
  size_t folded_before = folded_edges(mesh);
  set_positions(mesh, positions);
  MeshStatistics s = mesh_statistics(mesh);
  EXPECT_EQ(s.quads, s.faces);
  EXPECT_EQ(s.euler_characteristic, mesh_statistics(f.initial.mesh).euler_characteristic);
  EXPECT_EQ(intersecting_face_pairs(mesh).size(), 0u);
  EXPECT_LE(folded_edges(mesh), folded_before);
  TrueSurfaceDistance truth = measure_true_surface_distance(mesh, f.shape.surface);
  double coverage = cloud_to_mesh_relative_to_local_radius(mesh, f.shape.cloud, f.shape.surface).p95;
  RecordProperty("inward_area", std::to_string(truth.inward_area_fraction));
  RecordProperty("coverage_p95", std::to_string(coverage));
  RecordProperty("surface_mean", std::to_string(truth.relative.mean));
  if (c.faces_out) {
    EXPECT_LE(truth.inward_area_fraction, 0.005);
  }
  if (c.covered) {
    EXPECT_LE(coverage, 0.05);
  }
  if (c.close) {
    EXPECT_LE(truth.relative.mean, 0.02);
  }
  std::printf("%s %s: inward %.4f, cloud->mesh p95 %.4f r, mesh->surface mean %.4f r\n", c.label,
              backend->name().c_str(), truth.inward_area_fraction, coverage, truth.relative.mean);
}

INSTANTIATE_TEST_SUITE_P(Issue14, StandIns,
                         ::testing::Combine(::testing::ValuesIn(kStandIns), ::testing::ValuesIn(test::backend_kinds())),
                         test::case_and_backend_label<StandIn>);

}  // namespace
}  // namespace mcquad
