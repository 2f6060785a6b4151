#include "pipeline/prepare.h"

#include <malloc.h>

#include <algorithm>
#include <memory>

#include "cells/cell_facing.h"

namespace mcquad {

double median_bone_radius(const BoneAssignment& bones) {
  std::vector<double> radii = bones.bone_radius;
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}

double automatic_epsilon(double median_radius) { return 0.6 * median_radius; }

size_t cell_leaf_size(size_t requested, size_t points) {
  constexpr size_t kLeafSize = 6, kPointsAtLeafSize = 2000000;
  if (requested > 0) return requested;
  return std::max(kLeafSize, kLeafSize * points / kPointsAtLeafSize);
}

EvolutionSetup prepare_evolution(const SkeletonGraph& graph, const PointCloud& cloud, const InitialMeshOptions& options,
                                 size_t leaf_size, const std::string& source, SetupScope scope, StageTimer* timer,
                                 const OrientedSample* scan_normals) {
  StageTimer own_timer;
  StageTimer& stages = timer ? *timer : own_timer;
  EvolutionSetup setup;
  // The radii and the initial mesh need the surface's shape, not every
  // point: above kMaxSetupPoints they read an even sample of the (sorted)
  // cloud. At 10^8 points the index, the radii and the initial mesh took
  // 46 s and 2 GB on all of them (docs/PERFORMANCE.md).
  PointCloud sample;
  if (cloud.size() > kMaxSetupPoints) sample = strided_sample(cloud, kMaxSetupPoints);
  const PointCloud& shape_points = sample.empty() ? cloud : sample;
  // The index serves the radii and the initial mesh, then goes before the cells are built.
  auto cloud_index =
      stages.run("point_index", [&] { return std::make_unique<PointIndex<float>>(shape_points.points); });
  setup.bones =
      stages.run("radius", [&] { return assign_points_to_bones(graph, shape_points, source, cloud_index.get()); });
  setup.median_radius = median_bone_radius(setup.bones);
  setup.bones.release_per_point();  // only the radii are needed from here on
  setup.initial = stages.run("initial_mesh", [&] {
    return build_initial_mesh(graph, setup.bones, shape_points, options, source, cloud_index.get());
  });
  cloud_index.reset();
  sample = PointCloud();
  if (scope == SetupScope::kInitialMesh) return setup;
  setup.cells = stages.run("cells", [&] {
    return build_cell_tree(cloud, cell_leaf_size(leaf_size, cloud.size()), true, true,
                           longest_cell_by_radius(setup.initial.skeleton));
  });
  // nanoflann allocates its tree nodes in small pooled blocks that glibc
  // keeps after they are freed (about 70 MiB at 10^7 points); give them
  // back before the device and the metrics add their own.
  malloc_trim(0);
  if (scope == SetupScope::kCells) return setup;
  stages.run("cell_facing", [&] {
    if (scan_normals)
      orient_cells(setup.cells, *scan_normals);
    else
      orient_cells(setup.cells, cloud.oriented.empty() ? oriented_sample(cloud) : cloud.oriented);
    return 0;
  });
  setup.arrays = flatten_mesh(setup.initial.mesh);
  setup.regions = stages.run("regions", [&] {
    return build_skeleton_regions(setup.initial.skeleton, setup.cells, setup.arrays, setup.median_radius);
  });
  return setup;
}

}  // namespace mcquad
