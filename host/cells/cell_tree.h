#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "core/point_cloud.h"
#include "core/shared_math.h"

namespace mcquad {

//! The paper's point cells: the leaves of a balanced kd-tree over the cloud
//! (nanoflann's, built here step for step), flattened once into the arrays that both backends read (the
//! layout is documented in kernels/shared/mcq_cell_tree.h). Inner nodes keep
//! tight boxes for ray traversal and nearest-point queries.
struct CellTree {
  std::vector<float> points;           //!< 3 per point, reordered by cell
  std::vector<uint32_t> cell_offsets;  //!< cell c holds points [offsets[c], offsets[c+1])
  std::vector<float> cell_centroids;   //!< 3 per cell: the paper's g_l
  std::vector<float> cell_normals;     //!< 3 per cell: the paper's t_l (least-squares plane normal)
  //! 3 per cell: the unit direction of the scan's outward normals in the
  //! cell (cells/cell_facing.h); zero where they disagree or are unknown.
  std::vector<float> cell_facing;
  std::vector<float> node_bounds;      //!< 6 per node: min xyz, max xyz (leaves padded, see build_cell_tree)
  std::vector<int32_t> node_children;  //!< 2 per node; a leaf stores -1 - cell, -1
  int depth = 0;                       //!< longest root-to-leaf path, in edges
  double point_spacing = 0;            //!< the cloud's median nearest-neighbour distance (sampled)
  //! How far inside every node's box its points lie at least: the padding
  //! less a margin for the padding's rounding. The nearest-point search
  //! prunes on the boxes shrunk by it.
  float bounds_inset = 0;

  size_t cell_count() const { return cell_offsets.empty() ? 0 : cell_offsets.size() - 1; }
  size_t node_count() const { return node_children.size() / 2; }
  size_t point_count() const { return points.size() / 3; }
  size_t byte_size() const;
};

//! The cells as the shared kernel code reads them: pointers into `cells`,
//! which must outlive the view.
inline device::mcq_cells cells_view(const CellTree& cells) {
  return {cells.node_bounds.data(),    cells.node_children.data(), cells.cell_offsets.data(), cells.points.data(),
          cells.cell_centroids.data(), cells.cell_normals.data(),  cells.cell_facing.data(),  cells.bounds_inset};
}

//! The paper's error level e-bar: the mean over the vertices (`positions`,
//! 3 floats each) of the distance to the plane of the cell holding the
//! nearest cloud point. The serial backend and the metrics both take it here.
//! `nearest_cells`, when given (one per vertex, -1 for none), holds a guess
//! at each vertex's nearest cell and receives the cell found: the answer is
//! the same, found faster where the guess is near (mcq_vertex_error).
double mean_vertex_error(const CellTree& cells, const std::vector<float>& positions,
                         std::vector<int>* nearest_cells = nullptr);

//! Builds the cells with at most `leaf_size` points each. Leaf boxes are
//! padded by the cloud's median nearest-neighbour distance unless
//! `pad_boxes` is false (the paper's tight boxes). Throws UnsupportedError if the tree is deeper than
//! the traversal stack allows.
//! Unless `split_wide_leaves` is false (nanoflann's leaves exactly), a leaf
//! more than six times as long as the median leaf is split on until it is
//! not: such a leaf spans a gap between two walls. With `longest_leaf`, a
//! leaf longer than longest_leaf(its box's centre) is split on too (the
//! pipeline passes a fraction of the local tube radius).
using LongestLeaf = std::function<float(const Eigen::Vector3f& centre)>;
CellTree build_cell_tree(const PointCloud& cloud, size_t leaf_size, bool pad_boxes = true,
                         bool split_wide_leaves = true, const LongestLeaf& longest_leaf = {});

}  // namespace mcquad
