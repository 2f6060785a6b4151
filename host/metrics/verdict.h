#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "metrics/mesh_metrics.h"

namespace mcquad {

//! One pass/fail statement about a mesh: its figure, the bound it is held
//! to, and where to look when it fails.
struct VerdictCheck {
  std::string name;         //!< e.g. "intersecting_face_pairs"
  std::string description;  //!< what it means, in plain words
  double value = 0;
  double threshold = 0;
  //! How the value must compare with the threshold to pass.
  enum class Bound { kAtMost, kAtLeast, kAbove } bound = Bound::kAtMost;
  bool passed = true;
  std::vector<Eigen::Vector3d> sites;  //!< the worst places, when known
};

//! Every check of a fitted mesh. `passed` only when all of them pass: a mesh
//! with one crossing pair is not a good mesh, whatever its distances say.
struct Verdict {
  bool passed = true;
  std::vector<VerdictCheck> checks;
  std::vector<const VerdictCheck*> failures() const;
  //! The check called `name` (nullptr when the verdict has none: a distance
  //! check without a median radius, say).
  const VerdictCheck* find(const std::string& name) const;
};

//! The bounds, as fractions of the median local radius where they are lengths.
struct VerdictThresholds {
  double inward_area_fraction = 0.005;   //!< area facing inward, of the mesh's area
  double cloud_to_mesh_p95 = 0.05;       //!< uncovered cloud: 95 % of the points within this
  double mesh_to_cloud_mean = 0.02;      //!< the mesh's mean distance to the cloud (plus the cloud's spacing)
  double min_scaled_jacobian = 0.0;      //!< every quad's corners keep their orientation
  double error_level_per_spacing = 1.0;  //!< the paper's error level, in point spacings
};

//! Judges a mesh by its metrics. `median_radius` scales the distances (0:
//! the distance checks are left out, as nothing says what is near).
//! `open_ends`: the boundary loops the mesh must have, one per open end the
//! construction left against the skeleton (-1: not checked).
Verdict judge_mesh(const QualityMetrics& metrics, double median_radius, long open_ends = -1,
                   const VerdictThresholds& thresholds = VerdictThresholds());

//! A check from its figure and bound (passed set from them).
VerdictCheck make_check(std::string name, std::string description, double value, VerdictCheck::Bound bound,
                        double threshold);

//! Adds a check made after the mesh was judged (the surfaces' own), keeping
//! `passed` the conjunction of all checks.
void add_check(Verdict& verdict, VerdictCheck check);

//! {"passed", "checks": [{"name", "passed", "value", "threshold", "comparison", "description", "sites"}]}
nlohmann::json to_json(const Verdict& verdict);

//! One line per failed check, for stderr: its figure, the bound and the first sites.
std::vector<std::string> verdict_warnings(const Verdict& verdict);

}  // namespace mcquad
