#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "metrics/surface_distance.h"
#include "surfaces/patch_layout.h"
#include "surfaces/spline_interpolation.h"

namespace mcquad {

//! Where the surfaces meet only in position: an irregular vertex and the
//! largest normal gap on the seams within reach of it.
struct NormalGapSite {
  int vertex = -1;
  int valence = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double max_normal_gap_degrees = 0;
  double mesh_crease_degrees = 0;  //!< the quad mesh's own largest dihedral angle at the vertex
};

//! How well the B-spline surfaces stand for the mesh and the cloud, and how
//! they meet each other. Sampled on every face's span (3 x 3 points) and on
//! every seam edge (5 points, evaluated from both sides).
struct SurfaceChecks {
  size_t surfaces = 0, periodic_surfaces = 0, samples = 0;
  DistanceSummary to_cloud;        //!< samples to their nearest cloud point (no cloud: zeros)
  DistanceSummary mesh_to_cloud;   //!< the quad mesh's own (face samples), for comparison
  DistanceSummary to_mesh;         //!< samples to the quad mesh
  size_t seam_edges = 0;
  double max_position_gap = 0;     //!< across all seams
  double tangent_tolerance_degrees = 0;
  size_t seam_edges_within_tolerance = 0;  //!< tangent planes agree within the tolerance
  double max_normal_gap_degrees = 0;
  //! The largest normal gap on seam edges at least `far_edges` edges away
  //! from every irregular vertex where the quad mesh itself is smooth (no
  //! dihedral angle above `smooth_mesh_degrees` at either end of the edge):
  //! what the construction adds, as opposed to creases the mesh already has.
  double max_normal_gap_away_from_irregular_degrees = 0;
  int far_edges = 2;
  double smooth_mesh_degrees = 30;
  //! Seam edges above the tolerance where the mesh is smooth lie within this
  //! many edges of an irregular vertex (-1: none).
  int farthest_gap_from_irregular = -1;
  //! Seam edges above the tolerance at a crease of the mesh itself.
  size_t gaps_at_mesh_creases = 0;
  std::vector<NormalGapSite> sites;  //!< irregular vertices with a gap above the tolerance, worst first
};

//! Samples the surfaces (one per layout region) against the mesh, the cloud
//! (may be null) and each other.
SurfaceChecks check_surfaces(const QuadMesh& mesh, const PatchLayout& layout,
                             const std::vector<BSplineSurface>& surfaces, const PointCloud* cloud,
                             double tangent_tolerance_degrees = 1.0);

nlohmann::json to_json(const SurfaceChecks& checks);

}  // namespace mcquad
