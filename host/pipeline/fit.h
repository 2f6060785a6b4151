#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/quad_mesh.h"
#include "evolution/evolution_backend.h"
#include "evolution/evolution_parameters.h"
#include "mesh/initial_mesh.h"
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
  SurfaceOutputs surfaces;           //!< B-spline surfaces to write (none by default)
};

struct FitResult {
  QuadMesh mesh;
  nlohmann::json report;
};

//! The whole pipeline: read, skeleton graph, radii, initial mesh, cells,
//! Monte Carlo evolution, metrics. The report holds the parameters as used,
//! per-iteration error level and time, backend and device, stage timings,
//! mesh statistics and quality metrics.
FitResult run_fit(const std::string& points_path, const std::string& skeleton_path, const FitOptions& options);

}  // namespace mcquad
