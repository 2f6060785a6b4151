#include "pipeline/measure.h"

#include <memory>

#include "cells/cell_tree.h"
#include "metrics/mesh_metrics.h"
#include "pipeline/prepare.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

nlohmann::json measure_mesh(const QuadMesh& mesh, const PointCloud& cloud, const SkeletonData* skeleton,
                            const std::string& skeleton_name, size_t leaf_size) {
  CellTree cells = build_cell_tree(cloud, cell_leaf_size(leaf_size, cloud.size()));
  std::unique_ptr<SkeletonGraph> graph;
  if (skeleton) graph = std::make_unique<SkeletonGraph>(build_skeleton_graph(*skeleton, skeleton_name));
  return to_json(measure_quality(mesh, cloud, cells, graph.get()));
}

}  // namespace mcquad
