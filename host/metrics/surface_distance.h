#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "cells/cell_tree.h"
#include "core/point_cloud.h"
#include "core/quad_mesh.h"

namespace mcquad {

struct DistanceSummary {
  double mean = 0, p95 = 0, max = 0;
};

//! Summary of a list of distances (mean, 95th percentile, max).
DistanceSummary summarize_distances(std::vector<double> distances);

//! {"mean", "p95", "max"} for reports.
nlohmann::json to_json(const DistanceSummary& distances);

//! Distance of every mesh vertex to its nearest cloud point, searched in the
//! cells (which hold every point), so no second index of the cloud is built.
std::vector<double> mesh_to_cloud_distances(const QuadMesh& mesh, const CellTree& cells);

//! Distance of every cloud point to the mesh surface (quads split into two
//! triangles), exact: the nearest triangle from one TriangleTree
//! (mesh/triangle_tree.h). With `max_points` > 0, every k-th point only, so
//! that at most that many are measured (huge clouds): distance k is of point
//! k * cloud_sample_stride(cloud.size(), max_points).
std::vector<double> cloud_to_mesh_distances(const QuadMesh& mesh, const PointCloud& cloud, size_t max_points = 0);

}  // namespace mcquad
