#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

#include "skeleton/voxel_graph.h"

namespace mcquad {

//! One connected piece of a band of geodesic distance from the root: on a
//! tube, a ring around it; where limbs branch, the ring splits.
struct LevelSetNode {
  int band = 0;
  std::vector<uint32_t> voxels;
  Eigen::Vector3d centre;  //!< of the circle through the piece (its centroid where no circle fits)
  double radius = 0;       //!< mean distance of its voxels from `centre`
  double widest_gap = 0;   //!< widest angle (radians) around `centre` with no voxel: small on a ring, large on an arc
};

//! The Reeb graph of geodesic distance (Verroust & Lazarus 1999): a node per
//! piece of each band of width `band_width`, an edge where pieces of
//! neighbouring bands touch.
struct LevelSetGraph {
  std::vector<LevelSetNode> nodes;
  std::vector<std::array<int, 2>> edges;
};

//! Builds it from the distances of every voxel (infinite or negative ones,
//! e.g. of discarded voxels, are left out).
LevelSetGraph build_level_set_graph(const VoxelGraph& graph, const std::vector<double>& distance, double band_width);

//! The centre of the circle best fitting `points` in their mean plane (Kasa's
//! algebraic fit): on a ring cut from a tube, its axis point whatever the
//! sampling density around the ring, where the centroid would lean toward the
//! denser side, e.g. the outside of a bend. Also the widest angular gap
//! around that centre. Falls back to the centroid on too few or collinear points.
struct RingFit {
  Eigen::Vector3d centre;
  double radius = 0;
  double widest_gap = 0;
};
RingFit fit_ring(const std::vector<Eigen::Vector3d>& points);

}  // namespace mcquad
