#include "pipeline/prepare.h"

#include <algorithm>

namespace mcquad {

double median_bone_radius(const BoneAssignment& bones) {
  std::vector<double> radii = bones.bone_radius;
  std::nth_element(radii.begin(), radii.begin() + radii.size() / 2, radii.end());
  return radii[radii.size() / 2];
}

double automatic_epsilon(double median_radius) { return 0.6 * median_radius; }

EvolutionSetup prepare_evolution(const SkeletonGraph& graph, const PointCloud& cloud, const InitialMeshOptions& options,
                                 size_t leaf_size, const std::string& source) {
  EvolutionSetup setup;
  PointIndex<float> cloud_index(cloud.points);
  setup.bones = assign_points_to_bones(graph, cloud, source, &cloud_index);
  setup.median_radius = median_bone_radius(setup.bones);
  setup.initial = build_initial_mesh(graph, setup.bones, cloud, options, source, &cloud_index);
  setup.cells = build_cell_tree(cloud, leaf_size);
  setup.arrays = flatten_mesh(setup.initial.mesh);
  return setup;
}

}  // namespace mcquad
