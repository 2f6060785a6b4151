#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "metrics/verdict.h"
#include "surfaces/cad_model.h"
#include "surfaces/surface_checks.h"

namespace mcquad {

struct SurfaceOutputs {
  std::string cad_path;                    //!< .step/.stp or .iges/.igs; empty: none
  std::string control_nets_path;           //!< the poles as a quad mesh (.obj, ...); empty: none
  double tangent_tolerance_degrees = 1.0;  //!< seams within this normal gap count as tangent-continuous
  std::string units = "mm";                //!< the length unit the CAD file declares (coordinates unchanged)
};

//! The CAD file as written and as OpenCASCADE reads it back.
struct CadFileReport {
  std::string path, units;
  size_t faces_written = 0;
  CadFileContents read_back;
  double seconds = 0;
};

//! What export_surfaces did: the patch layout, the file, the checks.
struct SurfaceReport {
  size_t regions = 0, irregular_vertices = 0, separatrix_edges = 0, single_face_fallbacks = 0;
  double fit_seconds = 0;
  std::optional<CadFileReport> cad_file;  //!< when a CAD path was given
  SurfaceChecks checks;
  double checks_seconds = 0;
};

//! The report's "surfaces" section.
nlohmann::json to_json(const SurfaceReport& report);

//! From the final quad mesh to CAD: regular regions, one interpolating
//! bicubic B-spline surface each, sewn and written through OpenCASCADE, then
//! read back and measured (against the cloud when given).
//! With a cloud and `off_cloud_check`, that check is set to the surfaces'
//! verdict check: no face's surface farther from the cloud than the quad mesh.
SurfaceReport export_surfaces(const QuadMesh& mesh, const PointCloud* cloud, const SurfaceOutputs& outputs,
                              VerdictCheck* off_cloud_check = nullptr);

}  // namespace mcquad
