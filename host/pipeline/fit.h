#pragma once

#include <optional>
#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "io/skeleton_io.h"
#include "pipeline/fit_options.h"
#include "pipeline/fit_report.h"

namespace mcquad {

//! What a fit starts from, already in memory (the Python package passes
//! numpy arrays): the cloud, the skeleton as read, and the names that error
//! messages and the report give them (a file's path, or a description).
//! A skeleton with no nodes and no name is extracted from the cloud first
//! (skeleton/cloud_skeleton.h).
struct FitInput {
  PointCloud cloud;
  SkeletonData skeleton;
  std::string points_name = "points";
  std::string skeleton_name = "skeleton";
};

struct FitResult {
  QuadMesh mesh;
  QuadMesh initial_mesh;                           //!< when FitOptions::keep_initial_mesh
  FitReport report;                                //!< its verdict set when measured (mcquad fit; not mcquad init)
  std::optional<SkeletonData> extracted_skeleton;  //!< when none was given
};

//! The whole pipeline: read, skeleton graph, radii, initial mesh, cells,
//! Monte Carlo evolution, metrics. The report holds the parameters as used,
//! per-iteration error level and time, backend and device, stage timings,
//! mesh statistics and quality metrics (pipeline/fit_report.h). An empty `skeleton_path`: the
//! skeleton is extracted from the cloud (report: "skeleton_extraction").
FitResult run_fit(const std::string& points_path, const std::string& skeleton_path, const FitOptions& options);

//! The same pipeline from a cloud and a skeleton in memory: for the same
//! data and options, the same mesh as from files, bit for bit. InputError
//! for an empty cloud, non-finite coordinates or bones naming no node.
FitResult run_fit(FitInput input, const FitOptions& options);

}  // namespace mcquad
