#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "metrics/verdict.h"

namespace mcquad {

struct SurfaceOutputs {
  std::string cad_path;                   //!< .step/.stp or .iges/.igs; empty: none
  std::string control_nets_path;          //!< the poles as a quad mesh (.obj, ...); empty: none
  double tangent_tolerance_degrees = 1.0; //!< seams within this normal gap count as tangent-continuous
  std::string units = "mm";               //!< the length unit the CAD file declares (coordinates unchanged)
};

//! From the final quad mesh to CAD: regular regions, one interpolating
//! bicubic B-spline surface each, sewn and written through OpenCASCADE, then
//! read back and measured (against the cloud when given). Returns the
//! report's "surfaces" section.
//! With a cloud and `off_cloud_check`, that check is set to the surfaces'
//! verdict check: no face's surface farther from the cloud than the quad mesh.
nlohmann::json export_surfaces(const QuadMesh& mesh, const PointCloud* cloud, const SurfaceOutputs& outputs,
                               VerdictCheck* off_cloud_check = nullptr);

}  // namespace mcquad
