#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "evolution/evolve.h"
#include "evolution/turned_face_smoothing.h"
#include "evolution/uncovered_reach.h"
#include "metrics/mesh_metrics.h"
#include "metrics/verdict.h"
#include "pipeline/fit_options.h"
#include "pipeline/skeleton_extraction.h"
#include "pipeline/stage_timer.h"
#include "pipeline/surfaces.h"

namespace mcquad {

//! What a fit did, typed: the CLI prints from it, the Python package and
//! `--report` get it as JSON through to_json, the one place it is spelled.
struct FitReport {
  struct Inputs {
    std::string points, skeleton;  //!< names as errors give them
    size_t point_count = 0, skeleton_nodes = 0, skeleton_bones = 0;
    int skeleton_components = 0;
  };
  //! The options as used: automatic values resolved.
  struct Parameters {
    FitOptions options;
    double epsilon = 0, median_radius = 0;
    size_t leaf_size = 0;
  };
  struct InitialMeshSummary {
    int open_ends = 0, refinement_levels = 0;
    MeshStatistics statistics;
    //! Coarse to fine: levels added after the evolution at this resolution.
    int levels_after_coarse_evolution = 0;
    int inset_ports = 0;  //!< InitialMesh::inset_ports
  };
  //! Robust mode at the default resolution (pipeline/fit.cpp,
  //! refine_where_uncovered): the fit refined once where it left the cloud
  //! uncovered, and which of the two fits was kept.
  struct CoverageRefinement {
    double bound = 0;                 //!< the verdict's bound on cloud -> mesh p95 over the median radius
    double uncovered_at_default = 0;  //!< that measure at the default resolution
    bool refined = false;             //!< it was over the bound: refined once and evolved again
    double uncovered_refined = 0;     //!< the measure one level finer (when refined)
    std::vector<std::string> worse;   //!< the refined fit's checks worse than the default fit's
    bool kept = false;                //!< the refined fit is the result
  };
  struct Cells {
    size_t cells = 0, tree_nodes = 0;
    int depth = 0;
    double megabytes = 0;
    double facing_fraction = 0;  //!< share of the cells the scan's normals gave a facing (cells/cell_facing.h)
  };
  struct Evolution {
    std::string backend, device;
    double initial_error_level = 0;
    std::vector<IterationRecord> iterations;
    std::string stop_reason;
    //! Robust mode on a scan with normals: the faces turned against them, smoothed after the evolution.
    std::optional<TurnedFaceSmoothing> turned_faces;
    //! Robust mode: the cloud left uncovered, pulled to after the evolution.
    std::optional<UncoveredReach> uncovered_reach;
    double final_error_level() const {
      return iterations.empty() ? initial_error_level : iterations.back().error_level;
    }
  };

  Inputs inputs;
  Parameters parameters;
  std::optional<SkeletonReport> skeleton_extraction;  //!< when no skeleton was given
  InitialMeshSummary initial_mesh;
  std::optional<Cells> cells;          //!< when built (fit, or init measuring)
  std::optional<Evolution> evolution;  //!< mcquad fit, not mcquad init
  //! Coarse to fine (finer than the default resolution, robust mode): the
  //! evolution at the default resolution before the mesh was refined.
  std::optional<Evolution> coarse_evolution;
  std::optional<CoverageRefinement> coverage_refinement;  //!< when judged (--refine-uncovered)
  std::optional<QualityMetrics> metrics;                  //!< when measured
  std::optional<Verdict> verdict;                         //!< when measured
  std::optional<SurfaceReport> surfaces;                  //!< when B-spline surfaces were asked for
  std::map<std::string, StageTimer::Record> stages;       //!< every stage run, by name
  double peak_resident_megabytes = 0;
  std::string output_mesh;  //!< the mesh file's absolute path, once written (empty: not written)
};

//! The report as `--report` writes it.
nlohmann::json to_json(const FitReport& report);

}  // namespace mcquad
