#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "mesh/triangle_tree.h"

namespace mcquad {

//! The exact nearest triangle for many queries in spatial order (the cloud
//! → mesh distances): for each triangle t, the triangles whose boxes come
//! within reach(t), the diagonal of t's box, of t's box. A query q nearer
//! than reach(t) / 2 to t has its nearest triangle among them (a triangle
//! nearer to q than t is lies within twice that distance of t), so with the
//! previous query's triangle as t it tests a few neighbours' boxes instead
//! of descending the tree, nearest box first, and stops at the first box
//! too far away to hold a nearer triangle; a query farther from t descends
//! the tree.
class TriangleNeighbourhoods {
 public:
  //! `tree` must outlive this.
  explicit TriangleNeighbourhoods(const TriangleTree& tree);

  //! As TriangleTree::nearest(p, hint): the same distance.
  std::pair<double, long> nearest(const Eigen::Vector3d& p, long hint) const;

 private:
  struct Neighbour {
    double gap;  //!< between the two triangles' boxes
    int triangle;
  };
  const TriangleTree& tree_;
  std::vector<double> reach_;          //!< per triangle
  std::vector<size_t> offsets_;        //!< triangle t's neighbours are neighbours_[offsets_[t], offsets_[t + 1])
  std::vector<Neighbour> neighbours_;  //!< nearest box first
};

}  // namespace mcquad
