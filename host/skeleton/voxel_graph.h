#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

namespace mcquad {

//! The cloud thinned to one point per occupied voxel (the mean of the points
//! in it) and joined to its occupied neighbours: a graph along the surface on
//! which geodesic distances are computed. One sample per voxel makes every
//! later stage independent of the scanner's density (tenfold changes along a
//! scan weigh the same), and the voxel count, not the point count, sets the
//! cost of everything after the binning pass.
struct VoxelGraph {
  double voxel_size = 0;
  std::vector<Eigen::Vector3d> centroids;  //!< per voxel, the mean of its points
  std::vector<uint32_t> offsets;           //!< CSR: neighbours of v are [offsets[v], offsets[v+1])
  std::vector<uint32_t> neighbours;
  std::vector<float> lengths;  //!< distance between the two centroids, per entry

  size_t size() const { return centroids.size(); }
};

//! The voxel edge that makes about `target_voxels` voxels occupied on this
//! cloud (a surface's voxel count falls with the square of the edge), found
//! on a strided sample of at most 200,000 points.
double voxel_size_for(const std::vector<Eigen::Vector3f>& points, size_t target_voxels);

//! The spacing of the cloud where it is sparsest: the 90th percentile of the
//! distance from a point to its nearest neighbour (over about 2000 points).
//! Voxels smaller than about twice it leave holes in sparse parts of a scan
//! that split the graph.
double sparse_spacing(const std::vector<Eigen::Vector3f>& points);

//! Bins the points into voxels of edge `voxel_size` and joins every pair of
//! occupied voxels among the 26 neighbours whose centroids are within twice
//! the edge: close enough to be the same sheet of surface, far enough apart
//! that two surfaces passing three edges apart stay unjoined. Voxels are
//! numbered in the order the points first reach them (deterministic).
VoxelGraph build_voxel_graph(const std::vector<Eigen::Vector3f>& points, double voxel_size);

//! Connected components: a label per voxel, numbered from 0; `count` gets their number.
std::vector<int> voxel_components(const VoxelGraph& graph, int& count);

//! Shortest-path lengths along the graph from the nearest of `sources`
//! (infinity where none is reachable).
std::vector<double> geodesic_distances(const VoxelGraph& graph, const std::vector<uint32_t>& sources);

}  // namespace mcquad
