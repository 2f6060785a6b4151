#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "core/point_index.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! Nearest-bone queries against a skeleton graph: a kd-tree over dense
//! samples along the bones finds the neighbourhood, then the exact segment
//! distances to the bones sharing the nearest sample bone's nodes decide.
class NearestBone {
 public:
  explicit NearestBone(const SkeletonGraph& graph);

  struct Hit {
    int bone = -1;
    double parameter = 0;  //!< projection onto the bone, in [0, 1]
    double distance = 0;
  };
  Hit find(const Eigen::Vector3d& p) const;

 private:
  const SkeletonGraph& graph_;
  std::vector<int> sample_bone_;  // before samples_, which are built filling it
  std::vector<Eigen::Vector3d> samples_;
  std::vector<std::vector<int>> node_bones_;
  PointIndex<double> index_;
};

}  // namespace mcquad
