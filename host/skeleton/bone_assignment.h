#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/point_cloud.h"
#include "core/point_index.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! Every cloud point assigned to its nearest bone (skeleton edge), with the
//! projection parameter along the bone and the distance to it; and from
//! that, robust local radii of the cloud around bones and nodes.
struct BoneAssignment {
  std::vector<int> bone;            //!< per point: index into graph.edges
  std::vector<float> parameter;     //!< per point: projection onto the bone in [0, 1]
  std::vector<float> distance;      //!< per point: distance to the bone
  std::vector<double> bone_radius;  //!< median distance of the bone's points
  std::vector<double> node_radius;  //!< per skeleton node, see assign_points_to_bones

  //! Frees the per-point arrays (12 bytes a point) once only radii are needed.
  void release_per_point() {
    std::vector<int>().swap(bone);
    std::vector<float>().swap(parameter);
    std::vector<float>().swap(distance);
  }
};

//! Assigns points to bones and estimates radii. A bone's radius is the median
//! distance of its points that project inside it (points past its ends belong
//! to caps and junction blobs); medians keep noise and outliers from moving
//! it. A node's radius is the mean of its bones' radii, the smallest of them
//! at a junction. A bone no point is nearest to (inside a thick body, where
//! other bones are nearer to the surface everywhere) takes the cloud's
//! distance from it. Throws InputError (prefixed by `source`) when the
//! skeleton does not match the cloud: a bone without points far outside the
//! cloud, a node far outside it, or most points far from every bone.
//! `cloud_index` (over cloud.points) is built here when not given.
BoneAssignment assign_points_to_bones(const SkeletonGraph& graph, const PointCloud& cloud, const std::string& source,
                                      const PointIndex<float>* cloud_index = nullptr);

//! Distance from p to segment [a, b] and the projection parameter in [0, 1].
//! Per node, the radius of the widest of its bones (0 at a node no bone
//! ends at): a junction on a trunk's axis lies the trunk's radius from its
//! surface, however thin a branch leaving it.
std::vector<double> widest_bone_radii(size_t node_count, const std::vector<std::array<int, 2>>& edges,
                                      const std::vector<double>& bone_radius);

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double* t);

}  // namespace mcquad
