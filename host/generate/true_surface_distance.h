#pragma once

#include <nlohmann/json.hpp>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "generate/tube_surface.h"
#include "metrics/surface_distance.h"

namespace mcquad {

//! Distances of the mesh vertices to a generated shape's true surface, in
//! model units and relative to the local tube radius (the nearest capsule's).
struct TrueSurfaceDistance {
  DistanceSummary absolute, relative;
  //! The mean of the signed distances relative to the local radius: below
  //! zero where the vertices settle inside the surface on average.
  double signed_relative_mean = 0;
  //! The share of the mesh's area whose faces point against the true
  //! surface's outward normal near them (issue 20: turned-over faces in the
  //! creases where tubes meet).
  double inward_area_fraction = 0;
};
TrueSurfaceDistance measure_true_surface_distance(const QuadMesh& mesh, const TubeSurface& surface);

//! The share of the mesh's area facing inward against the true surface: a
//! face faces inward when its normal points against the gradient of the
//! union's signed distance at its centre, which is the outward normal at the
//! nearest point of the surface (inside, where capsules overlap, the normal
//! of the nearest capsule's wall: signed_distance is a lower bound there).
double inward_area_fraction(const QuadMesh& mesh, const TubeSurface& surface);

//! Distances of the cloud points to the mesh relative to their local tube
//! radius (the nearest capsule's): issue 6's coverage, "95 % of the points
//! within 5 % of the local radius", where radii differ along the shape.
DistanceSummary cloud_to_mesh_relative_to_local_radius(const QuadMesh& mesh, const PointCloud& cloud,
                                                       const TubeSurface& surface);

nlohmann::json to_json(const TrueSurfaceDistance& distance);

}  // namespace mcquad
