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
  //! `tree` must outlive this. The lists are built only for at least
  //! kLeastQueriesPerTriangle `queries` per triangle; for fewer they cost
  //! more to build than they save, and every query descends the tree.
  //! Measured on the knot's 413,696 points (docs/PERFORMANCE.md): at 23 a
  //! triangle (its default mesh) the two ways take about as long; at 5.9
  //! and 1.5 the lists made the metrics 1.3 and 1.6 times slower, and at
  //! 0.09 (2.26 million vertices) they took 4 GB.
  TriangleNeighbourhoods(const TriangleTree& tree, size_t queries);
  static constexpr double kLeastQueriesPerTriangle = 16.0;

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
