#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

namespace mcquad {

//! Nearest-point search over points already in spatial order
//! (sort_spatially). The tree is the points' Morton order cut at its
//! highest differing bits (a binary radix tree, as linear bounding-volume
//! hierarchies are built), down to leaves of at most kLeafSize consecutive
//! points, with boxes fitted bottom up: no point moves, and the build is
//! linear. A kd-tree (PointIndex, nanoflann) partitions the points again at
//! every level: 70 ms for the knot's 413,696 points, against about 5 ms
//! here, for the few thousand queries of a mesh's faces
//! (docs/PERFORMANCE.md). On points in any other order the answers are the
//! same, only slower.
class SortedPointTree {
 public:
  static constexpr int kLeafSize = 8;

  //! `points` must outlive the tree and stay unchanged.
  explicit SortedPointTree(const std::vector<Eigen::Vector3f>& points);

  //! Index of the nearest point (the first of equally near ones) and its
  //! squared distance; (-1, infinity) when there are no points.
  std::pair<long, float> nearest(const Eigen::Vector3f& query) const;

 private:
  //! A leaf holds points [first, first + count); an inner node (count 0)
  //! has its children at nodes_[first] and nodes_[first + 1].
  struct Node {
    Eigen::AlignedBox3f box;
    long first = 0, count = 0;
  };
  //! Builds nodes_[node] over points [begin, end); cuts by Morton bits
  //! below `bit` only.
  void build(size_t node, long begin, long end, const std::vector<uint64_t>& codes, int bit);

  const std::vector<Eigen::Vector3f>& points_;
  std::vector<Node> nodes_;
};

}  // namespace mcquad
