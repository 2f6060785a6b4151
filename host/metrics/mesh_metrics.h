#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cells/cell_tree.h"
#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "mesh/folds.h"
#include "mesh/quad_shape.h"
#include "mesh/scan_orientation.h"
#include "metrics/inward_faces.h"
#include "metrics/mesh_statistics.h"
#include "metrics/surface_distance.h"
#include "metrics/winding_number.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! Everything `mcquad metrics` and fit's report state about a mesh.
struct QualityMetrics {
  MeshStatistics statistics;
  DistanceSummary mesh_to_cloud;
  DistanceSummary cloud_to_mesh;     //!< over at most a million evenly strided cloud points
  double error_level = 0;            //!< the paper's e-bar
  double cloud_spacing = 0;          //!< the cloud's median nearest-neighbour distance: no mesh is nearer on average
  long inward_faces = -1;            //!< faces facing inward (-1: nothing to tell inward by)
  double inward_area_fraction = -1;  //!< their share of the mesh's area (-1: not measured)
  std::string inward_reference;      //!< what "inward" is measured against: "scan normals" or "skeleton"
  size_t folded_edges = 0;           //!< edges between faces folded over each other
  size_t intersecting_face_pairs = 0;
  //! Where faces cross: the midpoint of each pair's face centroids, for the
  //! first kMaxCrossingSites pairs (a user looks there first).
  std::vector<Eigen::Vector3d> crossing_sites;
  static constexpr size_t kMaxCrossingSites = 100;
  //! The worst places for the other defects, worst first, at most kMaxSites each.
  static constexpr size_t kMaxSites = 5;
  std::vector<Eigen::Vector3d> fold_sites;        //!< midpoints of folded edges
  std::vector<Eigen::Vector3d> worst_quad_sites;  //!< centroids of the quads of least scaled Jacobian (at most 0)
  std::vector<Eigen::Vector3d> inward_sites;      //!< centroids of the largest faces facing inward
  std::vector<Eigen::Vector3d> uncovered_sites;   //!< the cloud points farthest from the mesh
  std::vector<Eigen::Vector3d> off_cloud_sites;   //!< the vertices farthest from the cloud
  std::vector<Eigen::Vector3d> boundary_sites;    //!< the centres of the mesh's boundary loops (holes and open ends)
  QuadShape quad_shape;
};

//! Measures a mesh against its cloud. Which faces face inward is told by the
//! scan's own normals when `scan` has any (the truth a user sees), else by
//! the skeleton when given (an approximation), else not measured.
QualityMetrics measure_quality(const QuadMesh& mesh, const PointCloud& cloud, const CellTree& cells,
                               const SkeletonGraph* skeleton, const ScanOrientation* scan = nullptr);

nlohmann::json to_json(const QualityMetrics& metrics);

}  // namespace mcquad
