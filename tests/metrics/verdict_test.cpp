// The verdict: every check passes on a good mesh's figures and fails on a
// bad one's, and the verdict fails when any check does.
#include "metrics/verdict.h"

#include <gtest/gtest.h>

namespace mcquad {
namespace {

//! Figures of a clean closed quad mesh fitted within 1 % of a radius of 1.
QualityMetrics good_metrics() {
  QualityMetrics m;
  m.statistics.faces = 1000;
  m.statistics.quad_fraction = 1.0;
  m.inward_faces = 0;
  m.inward_area_fraction = 0;
  m.inward_reference = "scan normals";
  m.quad_shape.min_scaled_jacobian = 0.6;
  m.cloud_to_mesh.p95 = 0.01;
  m.mesh_to_cloud.mean = 0.01;
  m.cloud_spacing = 0.005;
  return m;
}

const VerdictCheck& check_named(const Verdict& verdict, const std::string& name) {
  for (const auto& check : verdict.checks)
    if (check.name == name) return check;
  throw std::runtime_error("no check " + name);
}

TEST(Verdict, GoodFiguresPassEveryCheck) {
  QualityMetrics m = good_metrics();
  m.statistics.boundary_loops = 2;
  Verdict verdict = judge_mesh(m, 1.0, 2);
  EXPECT_TRUE(verdict.passed);
  EXPECT_EQ(verdict.checks.size(), 10u);
  EXPECT_TRUE(verdict.failures().empty());
  EXPECT_TRUE(verdict_warnings(verdict).empty());
}

struct BadFigure {
  const char* check;
  void (*spoil)(QualityMetrics&);
};

class VerdictFailsOn : public ::testing::TestWithParam<BadFigure> {};

TEST_P(VerdictFailsOn, OneBadFigure) {
  QualityMetrics m = good_metrics();
  GetParam().spoil(m);
  Verdict verdict = judge_mesh(m, 1.0, 0);
  EXPECT_FALSE(verdict.passed);
  ASSERT_EQ(verdict.failures().size(), 1u);
  EXPECT_EQ(verdict.failures()[0]->name, GetParam().check);
  EXPECT_FALSE(check_named(verdict, GetParam().check).passed);
  auto warnings = verdict_warnings(verdict);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find(GetParam().check), std::string::npos) << warnings[0];
}

INSTANTIATE_TEST_SUITE_P(
    EachCheck, VerdictFailsOn,
    ::testing::Values(
        BadFigure{"all_quads", [](QualityMetrics& m) { m.statistics.quad_fraction = 0.99; }},
        BadFigure{"non_manifold_vertices", [](QualityMetrics& m) { m.statistics.non_manifold_vertices = 1; }},
        BadFigure{"intersecting_face_pairs", [](QualityMetrics& m) { m.intersecting_face_pairs = 1; }},
        BadFigure{"folded_edges", [](QualityMetrics& m) { m.folded_edges = 2; }},
        BadFigure{"min_scaled_jacobian", [](QualityMetrics& m) { m.quad_shape.min_scaled_jacobian = -0.1; }},
        BadFigure{"inward_faces", [](QualityMetrics& m) { m.inward_area_fraction = 0.006; }},
        BadFigure{"uncovered_cloud", [](QualityMetrics& m) { m.cloud_to_mesh.p95 = 0.06; }},
        BadFigure{"mesh_off_cloud", [](QualityMetrics& m) { m.mesh_to_cloud.mean = 0.03; }},
        BadFigure{"open_ends", [](QualityMetrics& m) { m.statistics.boundary_loops = 1; }},
        BadFigure{"error_level", [](QualityMetrics& m) { m.error_level = 0.006; }}),
    [](const ::testing::TestParamInfo<BadFigure>& param) { return std::string(param.param.check); });

TEST(Verdict, CrossingSitesAreNamedInTheWarning) {
  QualityMetrics m = good_metrics();
  m.intersecting_face_pairs = 1;
  m.crossing_sites = {Eigen::Vector3d(1.5, -2, 3)};
  auto warnings = verdict_warnings(judge_mesh(m, 1.0));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("at (1.5, -2, 3)"), std::string::npos) << warnings[0];
}

TEST(Verdict, InwardAreaAtTheBoundPassesAndJustAboveFails) {
  QualityMetrics m = good_metrics();
  m.inward_area_fraction = 0.005;
  EXPECT_TRUE(check_named(judge_mesh(m, 1.0), "inward_faces").passed);
  m.inward_area_fraction = 0.0051;
  const VerdictCheck& check = check_named(judge_mesh(m, 1.0), "inward_faces");
  EXPECT_FALSE(check.passed);
  EXPECT_NE(check.description.find("scan normals"), std::string::npos) << check.description;
}

TEST(Verdict, ATornHoleIsNamedByItsBoundaryLoop) {
  QualityMetrics m = good_metrics();
  m.statistics.boundary_loops = 2;
  m.boundary_sites = {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(2, 0.5, 1)};
  const VerdictCheck& check = check_named(judge_mesh(m, 1.0, 1), "open_ends");
  EXPECT_FALSE(check.passed);
  EXPECT_EQ(check.sites.size(), 2u);
  EXPECT_TRUE(check_named(judge_mesh(m, 1.0, 2), "open_ends").passed);
}

TEST(Verdict, SparseCloudsAreAllowedTheirSpacing) {
  QualityMetrics m = good_metrics();
  m.cloud_spacing = 0.04;  // a vertex on the true surface is about this far from the nearest point
  m.mesh_to_cloud.mean = 0.055;
  EXPECT_TRUE(check_named(judge_mesh(m, 1.0), "mesh_off_cloud").passed);
  m.mesh_to_cloud.mean = 0.065;
  EXPECT_FALSE(check_named(judge_mesh(m, 1.0), "mesh_off_cloud").passed);
}

TEST(Verdict, WithoutASkeletonOrARadiusThoseChecksAreLeftOut) {
  QualityMetrics m = good_metrics();
  m.inward_faces = -1;
  m.inward_area_fraction = -1;
  m.cloud_spacing = 0;
  Verdict verdict = judge_mesh(m, 0.0);
  EXPECT_EQ(verdict.checks.size(), 5u);
  for (const auto& check : verdict.checks) {
    EXPECT_NE(check.name, "inward_faces");
    EXPECT_NE(check.name, "uncovered_cloud");
  }
}

TEST(Verdict, JsonHoldsEveryCheckWithItsBound) {
  QualityMetrics m = good_metrics();
  m.folded_edges = 3;
  nlohmann::json j = to_json(judge_mesh(m, 1.0));
  EXPECT_FALSE(j["passed"].get<bool>());
  ASSERT_EQ(j["checks"].size(), 9u);
  for (const auto& check : j["checks"]) {
    EXPECT_TRUE(check.contains("value") && check.contains("threshold") && check.contains("comparison"));
    if (check["name"] == "folded_edges") {
      EXPECT_FALSE(check["passed"].get<bool>());
      EXPECT_EQ(check["value"].get<double>(), 3.0);
      EXPECT_EQ(check["comparison"], "at most");
    }
  }
}

}  // namespace
}  // namespace mcquad
