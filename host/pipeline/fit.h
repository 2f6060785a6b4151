#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/quad_mesh.h"
#include "evolution/evolution_backend.h"
#include "evolution/evolution_parameters.h"
#include "io/skeleton_io.h"
#include "mesh/initial_mesh.h"
#include "metrics/verdict.h"
#include "pipeline/surfaces.h"

namespace mcquad {

struct FitOptions {
  EvolutionParameters evolution;
  InitialMeshOptions initial;
  size_t leaf_size = 0;              //!< at most this many points per cell; 0: automatic (cell_leaf_size)
  BackendKind backend = BackendKind::kAuto;
  std::string device;                //!< OpenCL device by index or name
  std::string snapshots_directory;   //!< write the mesh after every iteration here
  std::string construction_skeleton; //!< write the skeleton the mesh was built on here (OBJ)
  bool evolve = true;                //!< false: stop after the initial mesh (mcquad init)
  bool measure = true;               //!< compute quality metrics for the report
  bool keep_initial_mesh = false;    //!< return the initial mesh too (for the HTML report)
  SurfaceOutputs surfaces;           //!< B-spline surfaces to write (none by default)
};

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
  QuadMesh initial_mesh;           //!< when FitOptions::keep_initial_mesh
  nlohmann::json report;
  std::optional<Verdict> verdict;  //!< when measured (mcquad fit; not mcquad init)
  std::optional<SkeletonData> extracted_skeleton;  //!< when none was given
};

//! The whole pipeline: read, skeleton graph, radii, initial mesh, cells,
//! Monte Carlo evolution, metrics. The report holds the parameters as used,
//! per-iteration error level and time, backend and device, stage timings,
//! mesh statistics and quality metrics. An empty `skeleton_path`: the
//! skeleton is extracted from the cloud (report: "skeleton_extraction").
FitResult run_fit(const std::string& points_path, const std::string& skeleton_path, const FitOptions& options);

//! The same pipeline from a cloud and a skeleton in memory: for the same
//! data and options, the same mesh as from files, bit for bit. InputError
//! for an empty cloud, non-finite coordinates or bones naming no node.
FitResult run_fit(FitInput input, const FitOptions& options);

//! The range an option must lie in, in the units the CLI and the Python
//! package take it (angles in degrees). One table for both: the CLI checks
//! it while parsing, run_fit for every other caller.
struct OptionRange {
  const char* name;  //!< as the Python keyword: start_fraction, alpha_max, ...
  double low, high;
};
//! The range of a ranged option (InputError for a name without one).
const OptionRange& fit_option_range(const std::string& name);

//! Option words as the CLI and the Python package spell them. InputError
//! naming `option` and the accepted words for anything else.
EndMode end_mode_from_name(const std::string& name, const std::string& option = "ends");
BackendKind backend_from_name(const std::string& name, const std::string& option = "backend");
EvolutionParameters::Mode evolution_mode_from_name(const std::string& name, const std::string& option = "mode");

}  // namespace mcquad
