#include "cells/cell_tree.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>

#include "core/errors.h"
#include "core/point_index.h"
#include "core/shared_math.h"

namespace mcquad {
namespace {

struct CloudAdaptor {
  const PointCloud& cloud;
  size_t kdtree_get_point_count() const { return cloud.size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return cloud.points[i][dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, CloudAdaptor>, CloudAdaptor, 3>;
using KdNode = KdTree::Node;

//! Least-squares plane of a cell: centroid and the eigenvector of the
//! smallest eigenvalue of the 3x3 covariance (accumulated in double).
void fit_cell_plane(const float* points, size_t count, float* centroid, float* normal) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < count; ++i) mean += Eigen::Vector3f(points + 3 * i).cast<double>();
  mean /= double(count);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < count; ++i) {
    Eigen::Vector3d d = Eigen::Vector3f(points + 3 * i).cast<double>() - mean;
    covariance += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d t = solver.eigenvectors().col(0);
  // A fixed sign convention keeps the arrays reproducible.
  int largest;
  t.cwiseAbs().maxCoeff(&largest);
  if (t[largest] < 0) t = -t;
  for (int k = 0; k < 3; ++k) {
    centroid[k] = float(mean[k]);
    normal[k] = float(t[k]);
  }
}

class Flattener {
 public:
  Flattener(const PointCloud& cloud, const KdTree& tree, CellTree& out, float padding)
      : cloud_(cloud), tree_(tree), out_(out), padding_(padding) {}

  //! Appends `node` and its subtree in depth-first order; returns its index.
  int flatten(const KdNode* node, int level) {
    int index = int(out_.node_count());
    out_.node_children.insert(out_.node_children.end(), {-1, -1});
    out_.node_bounds.resize(out_.node_bounds.size() + 6);
    out_.depth = std::max(out_.depth, level);
    if (!node->child1 && !node->child2) {
      int cell = add_cell(node->node_type.lr.left, node->node_type.lr.right);
      out_.node_children[2 * index] = -1 - cell;
      set_bounds(index, out_.points.data() + 3 * out_.cell_offsets[cell],
                 out_.cell_offsets[cell + 1] - out_.cell_offsets[cell]);
      return index;
    }
    int left = flatten(node->child1, level + 1);
    int right = flatten(node->child2, level + 1);
    out_.node_children[2 * index] = left;
    out_.node_children[2 * index + 1] = right;
    for (int k = 0; k < 3; ++k) {
      out_.node_bounds[6 * index + k] = std::min(out_.node_bounds[6 * left + k], out_.node_bounds[6 * right + k]);
      out_.node_bounds[6 * index + 3 + k] =
          std::max(out_.node_bounds[6 * left + 3 + k], out_.node_bounds[6 * right + 3 + k]);
    }
    return index;
  }

 private:
  int add_cell(size_t first, size_t last) {
    int cell = int(out_.cell_count());
    for (size_t i = first; i < last; ++i) {
      size_t id = tree_.vAcc[i];
      out_.points.insert(out_.points.end(), cloud_.points[id].data(), cloud_.points[id].data() + 3);
    }
    out_.cell_offsets.push_back(uint32_t(out_.point_count()));
    out_.cell_centroids.resize(out_.cell_centroids.size() + 3);
    out_.cell_normals.resize(out_.cell_normals.size() + 3);
    fit_cell_plane(out_.points.data() + 3 * out_.cell_offsets[cell], last - first, &out_.cell_centroids[3 * cell],
                   &out_.cell_normals[3 * cell]);
    return cell;
  }

  //! A leaf's box: tight around its points, then padded by the cloud's
  //! typical point spacing. Tight boxes of neighbouring patches of a surface
  //! leave gaps a ray can slip through, and a vertex whose rays all slip
  //! through never moves; the padding closes the gaps (docs/DESIGN.md).
  void set_bounds(int node, const float* points, size_t count) {
    float* b = &out_.node_bounds[6 * node];
    for (int k = 0; k < 3; ++k) b[k] = b[3 + k] = points[k];
    for (size_t i = 1; i < count; ++i) {
      for (int k = 0; k < 3; ++k) {
        b[k] = std::min(b[k], points[3 * i + k]);
        b[3 + k] = std::max(b[3 + k], points[3 * i + k]);
      }
    }
    for (int k = 0; k < 3; ++k) {
      b[k] -= padding_;
      b[3 + k] += padding_;
    }
  }

  const PointCloud& cloud_;
  const KdTree& tree_;
  CellTree& out_;
  float padding_;
};

void count_nodes(const KdNode* node, size_t& nodes, size_t& leaves) {
  nodes += 1;
  if (!node->child1 && !node->child2) {
    leaves += 1;
    return;
  }
  count_nodes(node->child1, nodes, leaves);
  count_nodes(node->child2, nodes, leaves);
}

}  // namespace

size_t CellTree::byte_size() const {
  return points.size() * 4 + cell_offsets.size() * 4 + cell_centroids.size() * 4 + cell_normals.size() * 4 +
         node_bounds.size() * 4 + node_children.size() * 4;
}

CellTree build_cell_tree(const PointCloud& cloud, size_t leaf_size, bool pad_boxes) {
  if (cloud.empty()) throw InputError("cannot build cells: the point cloud is empty");
  if (cloud.size() >= size_t(UINT32_MAX)) throw UnsupportedError("clouds of 2^32 points or more are not supported");
  CloudAdaptor adaptor{cloud};
  KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(std::max<size_t>(leaf_size, 1)));
  tree.buildIndex();
  // Exact sizes up front: grown by doubling, the arrays of a 10^7-point
  // cloud would hold up to twice their size, and copy it at every step.
  size_t nodes = 0, leaves = 0;
  count_nodes(tree.root_node, nodes, leaves);
  CellTree cells;
  cells.points.reserve(3 * cloud.size());
  cells.cell_offsets.reserve(leaves + 1);
  cells.cell_centroids.reserve(3 * leaves);
  cells.cell_normals.reserve(3 * leaves);
  cells.node_bounds.reserve(6 * nodes);
  cells.node_children.reserve(2 * nodes);
  cells.cell_offsets.push_back(0);
  cells.point_spacing = median_neighbour_spacing(cloud.points, tree);
  Flattener(cloud, tree, cells, pad_boxes ? float(cells.point_spacing) : 0.0f).flatten(tree.root_node, 0);
  if (cells.depth > MCQ_MAX_TREE_DEPTH)
    throw UnsupportedError("the cell tree is " + std::to_string(cells.depth) + " levels deep, more than the " +
                           std::to_string(MCQ_MAX_TREE_DEPTH) + " the traversal supports (many duplicate points?)");
  return cells;
}

double mean_vertex_error(const CellTree& cells, const std::vector<float>& positions) {
  const device::mcq_cells view = cells_view(cells);
  const size_t vertices = positions.size() / 3;
  double sum = 0;
  for (size_t v = 0; v < vertices; ++v)
    sum += device::mcq_vertex_error(view, device::mcq_load3(positions.data(), uint32_t(v)));
  return vertices ? sum / double(vertices) : 0.0;
}

}  // namespace mcquad
