#pragma once

#include <vector>

#include "core/quad_mesh.h"
#include "surfaces/patch_layout.h"
#include "surfaces/spline_interpolation.h"

namespace mcquad {

//! A quad mesh turned into B-spline surfaces: its regular regions and one
//! interpolating surface per region (surfaces[k] belongs to regions[k]).
struct SurfaceModel {
  PatchLayout layout;
  std::vector<BSplineSurface> surfaces;
};

SurfaceModel build_surface_model(const QuadMesh& mesh);

//! The control nets as one quad mesh (a grid of poles per surface, closed
//! where the surface is periodic), for writing as OBJ.
QuadMesh control_net_mesh(const std::vector<BSplineSurface>& surfaces);

}  // namespace mcquad
