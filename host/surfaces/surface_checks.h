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

//! A face whose surface is farther from the cloud than the quad mesh is:
//! where a B-spline bulges away (near irregular vertices, typically).
struct OffCloudSurfaceSite {
  int face = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  //!< the face's sample farthest from the cloud
  double surface_distance = 0;                         //!< that sample's distance to the nearest cloud point
  double allowed_distance = 0;                         //!< the tolerance at this face
  int edges_from_irregular = -1;
};

//! How well the B-spline surfaces stand for the mesh and the cloud, and how
//! they meet each other. Sampled on every face's span (3 x 3 points) and on
//! every seam edge (5 points, evaluated from both sides).
struct SurfaceChecks {
  size_t surfaces = 0, periodic_surfaces = 0, samples = 0;
  DistanceSummary to_cloud;       //!< samples to their nearest cloud point (no cloud: zeros)
  DistanceSummary mesh_to_cloud;  //!< the quad mesh's own (face samples), for comparison
  DistanceSummary to_mesh;        //!< samples to the quad mesh
  //! Every face's surface must stay as near the cloud as the quad mesh: its
  //! farthest sample within 1.1 x the larger of the mesh's own p95 distance
  //! and the face's own farthest flat sample, plus the cloud's point spacing
  //! (the slack). The faces that do not, worst first (at most
  //! kMaxOffCloudSites kept; `faces_off_cloud` counts them all).
  double off_cloud_tolerance = 0;
  double off_cloud_slack = 0;
  size_t faces_off_cloud = 0;
  std::vector<OffCloudSurfaceSite> off_cloud_sites;
  static constexpr size_t kMaxOffCloudSites = 20;
  size_t seam_edges = 0;
  double max_position_gap = 0;  //!< across all seams
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
