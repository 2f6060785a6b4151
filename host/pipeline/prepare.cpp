#include "pipeline/prepare.h"

#include <algorithm>

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
                                 size_t leaf_size, const std::string& source) {
  EvolutionSetup setup;
  PointIndex<float> cloud_index(cloud.points);
  setup.bones = assign_points_to_bones(graph, cloud, source, &cloud_index);
  setup.median_radius = median_bone_radius(setup.bones);
  setup.initial = build_initial_mesh(graph, setup.bones, cloud, options, source, &cloud_index);
  setup.cells = build_cell_tree(cloud, cell_leaf_size(leaf_size, cloud.size()));
  setup.arrays = flatten_mesh(setup.initial.mesh);
  setup.regions = build_skeleton_regions(setup.initial.skeleton, setup.cells, setup.arrays, setup.median_radius);
  return setup;
}

}  // namespace mcquad
