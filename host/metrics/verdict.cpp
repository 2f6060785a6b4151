#include "metrics/verdict.h"

#include <cmath>
#include <cstdio>

namespace mcquad {
namespace {

constexpr size_t kSitesInWarning = 3;

using Bound = VerdictCheck::Bound;

const char* bound_words(Bound bound) {
  return bound == Bound::kAtMost ? "at most" : bound == Bound::kAtLeast ? "at least" : "above";
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

}  // namespace

VerdictCheck make_check(std::string name, std::string description, double value, Bound bound, double threshold) {
  VerdictCheck check;
  check.name = std::move(name);
  check.description = std::move(description);
  check.value = value;
  check.threshold = threshold;
  check.bound = bound;
  check.passed = bound == Bound::kAtMost    ? value <= threshold
                 : bound == Bound::kAtLeast ? value >= threshold
                                            : value > threshold;
  return check;
}

void add_check(Verdict& verdict, VerdictCheck check) {
  verdict.passed = verdict.passed && check.passed;
  verdict.checks.push_back(std::move(check));
}

std::vector<const VerdictCheck*> Verdict::failures() const {
  std::vector<const VerdictCheck*> failed;
  for (const auto& check : checks)
    if (!check.passed) failed.push_back(&check);
  return failed;
}

const VerdictCheck* Verdict::find(const std::string& name) const {
  for (const auto& check : checks)
    if (check.name == name) return &check;
  return nullptr;
}

Verdict judge_mesh(const QualityMetrics& m, double median_radius, long open_ends, const VerdictThresholds& t) {
  Verdict verdict;
  auto& checks = verdict.checks;
  checks.push_back(make_check("all_quads", "fraction of the faces that are quads", m.statistics.quad_fraction,
                              Bound::kAtLeast, 1.0));
  checks.push_back(make_check("non_manifold_vertices", "vertices where the surface is not a single sheet",
                              double(m.statistics.non_manifold_vertices), Bound::kAtMost, 0));
  checks.push_back(make_check("intersecting_face_pairs", "pairs of faces that cross each other",
                              double(m.intersecting_face_pairs), Bound::kAtMost, 0));
  checks.back().sites = m.crossing_sites;
  checks.push_back(make_check("folded_edges",
                              "edges whose two faces fold over each other (normals over 120 degrees apart)",
                              double(m.folded_edges), Bound::kAtMost, 0));
  checks.back().sites = m.fold_sites;
  checks.push_back(make_check("min_scaled_jacobian",
                              "the worst quad corner's signed sine (at or below 0: an inverted or degenerate quad)",
                              m.quad_shape.min_scaled_jacobian, Bound::kAbove, t.min_scaled_jacobian));
  checks.back().sites = m.worst_quad_sites;
  if (open_ends >= 0) {
    checks.push_back(make_check("open_ends",
                                "boundary loops of the mesh beyond the open ends of the skeleton's tubes "
                                "(a hole torn or an end closed that should not be)",
                                std::fabs(double(m.statistics.boundary_loops) - double(open_ends)), Bound::kAtMost, 0));
    checks.back().sites = m.boundary_sites;  // a torn hole is one of them; a closed end is missing
  }
  // The paper's error level is the mean distance to the cells' planes: on a
  // fitted mesh it is a fraction of the point spacing (0.23 on the T, 0.15
  // on the knot); a mesh still far from the cloud is many spacings off.
  if (m.cloud_spacing > 0)
    checks.push_back(make_check("error_level",
                                "the paper's error level (mean distance to the cells' planes), in point spacings",
                                m.error_level / m.cloud_spacing, Bound::kAtMost, t.error_level_per_spacing));
  if (m.inward_area_fraction >= 0 && m.statistics.faces > 0) {
    checks.push_back(make_check("inward_faces",
                                "share of the mesh's area facing inward (against the " +
                                    (m.inward_reference.empty() ? std::string("skeleton") : m.inward_reference) + ")",
                                m.inward_area_fraction, Bound::kAtMost, t.inward_area_fraction));
    checks.back().sites = m.inward_sites;
  }
  if (median_radius > 0) {
    checks.push_back(make_check("uncovered_cloud",
                                "95th percentile of the cloud's distance to the mesh, over the median local radius",
                                m.cloud_to_mesh.p95 / median_radius, Bound::kAtMost, t.cloud_to_mesh_p95));
    checks.back().sites = m.uncovered_sites;
    // A vertex exactly on the true surface is on average about one point
    // spacing from the nearest point (0.5 / sqrt(density) for random
    // samples, against 0.47 / sqrt(density) for the median spacing), so
    // the spacing is added to the allowance: the T at 60,000 points is
    // 0.0025 r from its true surface but 0.021 r from its nearest points,
    // with a spacing of 0.018 r.
    checks.push_back(make_check("mesh_off_cloud",
                                "mean distance of the mesh vertices to the nearest cloud point, over the median local "
                                "radius (bound: the threshold plus the cloud's point spacing)",
                                m.mesh_to_cloud.mean / median_radius, Bound::kAtMost,
                                t.mesh_to_cloud_mean + m.cloud_spacing / median_radius));
    checks.back().sites = m.off_cloud_sites;
  }
  for (const auto& check : checks) verdict.passed = verdict.passed && check.passed;
  return verdict;
}

nlohmann::json to_json(const Verdict& verdict) {
  nlohmann::json checks = nlohmann::json::array();
  for (const auto& c : verdict.checks) {
    nlohmann::json sites = nlohmann::json::array();
    for (const auto& p : c.sites) sites.push_back({p.x(), p.y(), p.z()});
    checks.push_back({{"name", c.name},
                      {"passed", c.passed},
                      {"value", c.value},
                      {"threshold", c.threshold},
                      {"comparison", bound_words(c.bound)},
                      {"description", c.description},
                      {"sites", sites}});
  }
  return {{"passed", verdict.passed}, {"checks", checks}};
}

std::vector<std::string> verdict_warnings(const Verdict& verdict) {
  std::vector<std::string> lines;
  for (const VerdictCheck* c : verdict.failures()) {
    std::string line = "check failed: " + c->name + " = " + format_number(c->value) + " (must be " +
                       bound_words(c->bound) + " " + format_number(c->threshold) + "): " + c->description;
    for (size_t i = 0; i < c->sites.size() && i < kSitesInWarning; ++i)
      line += std::string(i == 0 ? "; at " : ", ") + "(" + format_number(c->sites[i].x()) + ", " +
              format_number(c->sites[i].y()) + ", " + format_number(c->sites[i].z()) + ")";
    lines.push_back(line);
  }
  return lines;
}

}  // namespace mcquad
