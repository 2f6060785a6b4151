#include "cells/cell_tree.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/errors.h"
#include "core/point_index.h"
#include "core/shared_math.h"

namespace mcquad {
namespace {

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

//! A node of the tree while it is built: the range of points it holds and,
//! unless it is a leaf, its two halves.
struct BuildNode {
  size_t first = 0, last = 0;
  std::unique_ptr<BuildNode> child[2];
  bool is_leaf() const { return !child[0]; }
};

struct SplitBox {
  float low[3], high[3];
};

//! nanoflann's kd-tree construction (KDTreeSingleIndexAdaptor::divideTree,
//! middleSplit_, planeSplit, version 1.4.2), step for step, so the cells are
//! the ones the library builds -- tests/cells/cell_tree_test.cpp checks it --
//! but on the points themselves instead of an index array: every pass reads
//! memory in order, no 4-byte index a point is kept, the points end up in
//! cell order with no copy, and the two halves of a large node are built on
//! different cores. At 10^8 points: 26 s before, see docs/PERFORMANCE.md.
class CellTreeBuilder {
 public:
  CellTreeBuilder(std::vector<float>& xyz, size_t leaf_size, const LongestLeaf& longest_leaf)
      : xyz_(xyz), leaf_size_(leaf_size), longest_leaf_(longest_leaf) {}

  std::unique_ptr<BuildNode> build(bool split_wide) {
    auto root = std::make_unique<BuildNode>();
    root->last = xyz_.size() / 3;
    SplitBox box = bounds(0, root->last);
#pragma omp parallel
#pragma omp single
    divide(*root, box);
    if (split_wide) split_wide_leaves(*root);
    return root;
  }

 private:
  static constexpr size_t kParallelPoints = 1 << 16;
  static constexpr float kWidestLeaf = 6.0f;

  float at(size_t i, int axis) const { return xyz_[3 * i + size_t(axis)]; }

  void swap_points(size_t a, size_t b) {
    for (size_t k = 0; k < 3; ++k) std::swap(xyz_[3 * a + k], xyz_[3 * b + k]);
  }

  SplitBox bounds(size_t first, size_t last) const {
    SplitBox box{};
    for (int k = 0; k < 3; ++k) {
      float lo = at(first, k), hi = lo;
      for (size_t i = first + 1; i < last; ++i) {
        lo = std::min(lo, at(i, k));
        hi = std::max(hi, at(i, k));
      }
      box.low[k] = lo;
      box.high[k] = hi;
    }
    return box;
  }

  //! A leaf of the middle split holds at most leaf_size points but may span
  //! a gap: where a cell's box, split at its middle, holds a few points of
  //! two tubes' walls, the leaf stretches across the air between them, and
  //! a ray entering it averages both walls (random tree 5: a 4-point leaf
  //! over ten median leaves long, its points 2.1 apart on two tubes, drew
  //! the crease between them a radius out). Leaves longer than kWidestLeaf
  //! times the median leaf are split on until they are not, down to single
  //! points.
  void split_wide_leaves(BuildNode& root) {
    std::vector<BuildNode*> leaves;
    collect_leaves(root, leaves);
    std::vector<float> spans(leaves.size()), limits(leaves.size(), std::numeric_limits<float>::infinity());
#pragma omp parallel for schedule(static)
    for (long i = 0; i < long(leaves.size()); ++i) {
      const SplitBox box = bounds(leaves[size_t(i)]->first, leaves[size_t(i)]->last);
      spans[size_t(i)] = span(box);
      if (longest_leaf_)
        limits[size_t(i)] = longest_leaf_(
            0.5f * Eigen::Vector3f(box.low[0] + box.high[0], box.low[1] + box.high[1], box.low[2] + box.high[2]));
    }
    if (spans.empty()) return;
    std::vector<float> sorted = spans;
    std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
    const float widest = kWidestLeaf * sorted[sorted.size() / 2];
    // Leaves own disjoint runs of points, so each is split on its own.
    for (size_t i = 0; i < leaves.size(); ++i) {
      const float limit = std::min(widest, limits[i]);
      if (spans[i] > limit) split_while_wider(*leaves[i], limit);
    }
  }

  static void collect_leaves(BuildNode& node, std::vector<BuildNode*>& leaves) {
    if (node.is_leaf()) {
      leaves.push_back(&node);
      return;
    }
    for (auto& child : node.child) collect_leaves(*child, leaves);
  }

  //! The longest side of a box.
  static float span(const SplitBox& box) {
    return std::max({box.high[0] - box.low[0], box.high[1] - box.low[1], box.high[2] - box.low[2]});
  }

  void split_while_wider(BuildNode& node, float limit) {
    const size_t count = node.last - node.first;
    if (count < 2) return;
    const SplitBox box = bounds(node.first, node.last);
    if (!(span(box) > limit)) return;
    int axis = 0;
    float cut = 0;
    size_t index = split(node.first, count, box, axis, cut);
    index = std::clamp<size_t>(index, 1, count - 1);
    for (auto& child : node.child) child = std::make_unique<BuildNode>();
    node.child[0]->first = node.first;
    node.child[0]->last = node.child[1]->first = node.first + index;
    node.child[1]->last = node.last;
    for (auto& child : node.child) split_while_wider(*child, limit);
  }

  void divide(BuildNode& node, const SplitBox& box) {
    const size_t count = node.last - node.first;
    if (count <= leaf_size_) return;
    int axis = 0;
    float cut = 0;
    size_t index = split(node.first, count, box, axis, cut);
    for (auto& child : node.child) child = std::make_unique<BuildNode>();
    node.child[0]->first = node.first;
    node.child[0]->last = node.child[1]->first = node.first + index;
    node.child[1]->last = node.last;
    SplitBox low_box = box, high_box = box;
    low_box.high[axis] = cut;
    high_box.low[axis] = cut;
    if (count > kParallelPoints) {
#pragma omp task default(shared)
      divide(*node.child[0], low_box);
      divide(*node.child[1], high_box);
#pragma omp taskwait
    } else {
      divide(*node.child[0], low_box);
      divide(*node.child[1], high_box);
    }
  }

  //! middleSplit_: the axis of largest point spread among those whose box
  //! side is within 1e-5 of the longest, cut at the box's middle clamped to
  //! the points; returns where the upper half starts.
  size_t split(size_t first, size_t count, const SplitBox& box, int& axis, float& cut) {
    constexpr float kEps = 0.00001f;
    float max_span = box.high[0] - box.low[0];
    for (int k = 1; k < 3; ++k) max_span = std::max(max_span, box.high[k] - box.low[k]);
    float max_spread = -1, axis_min = 0, axis_max = 0;
    axis = 0;
    for (int k = 0; k < 3; ++k) {
      if (!(box.high[k] - box.low[k] > (1 - kEps) * max_span)) continue;
      float lo = at(first, k), hi = lo;
      for (size_t i = first + 1; i < first + count; ++i) {
        lo = std::min(lo, at(i, k));
        hi = std::max(hi, at(i, k));
      }
      if (hi - lo > max_spread) {
        axis = k;
        max_spread = hi - lo;
        axis_min = lo;
        axis_max = hi;
      }
    }
    if (max_spread < 0) {  // no side passed the test (NaN-free clouds always have one): as nanoflann, axis 0
      SplitBox tight = bounds(first, first + count);
      axis_min = tight.low[0];
      axis_max = tight.high[0];
    }
    float middle = (box.low[axis] + box.high[axis]) / 2;
    cut = middle < axis_min ? axis_min : middle > axis_max ? axis_max : middle;
    size_t below = 0, not_above = 0;
    plane_split(first, count, axis, cut, below, not_above);
    if (below > count / 2) return below;
    if (not_above < count / 2) return not_above;
    return count / 2;
  }

  //! planeSplit: points below `cut` first, then those equal to it, then the
  //! rest; `below` and `not_above` are where the second and third groups
  //! start. The same swaps as nanoflann's, so the same order.
  void plane_split(size_t first, size_t count, int axis, float cut, size_t& below, size_t& not_above) {
    size_t left = 0, right = count - 1;
    for (;;) {
      while (left <= right && at(first + left, axis) < cut) ++left;
      while (right && left <= right && at(first + right, axis) >= cut) --right;
      if (left > right || !right) break;
      swap_points(first + left, first + right);
      ++left;
      --right;
    }
    below = left;
    right = count - 1;
    for (;;) {
      while (left <= right && at(first + left, axis) <= cut) ++left;
      while (right && left <= right && at(first + right, axis) > cut) --right;
      if (left > right || !right) break;
      swap_points(first + left, first + right);
      ++left;
      --right;
    }
    not_above = left;
  }

  std::vector<float>& xyz_;
  size_t leaf_size_;
  const LongestLeaf& longest_leaf_;
};

//! Writes the built tree into the flat arrays, depth first (a node, its
//! lower half, its upper half), with tight boxes; the leaves come out in
//! the order of their point ranges.
int flatten(const BuildNode& node, int level, CellTree& out) {
  int index = int(out.node_count());
  out.node_children.insert(out.node_children.end(), {-1, -1});
  out.node_bounds.resize(out.node_bounds.size() + 6);
  out.depth = std::max(out.depth, level);
  float* b = &out.node_bounds[6 * size_t(index)];
  if (node.is_leaf()) {
    int cell = int(out.cell_count());
    out.cell_offsets.push_back(uint32_t(node.last));
    out.node_children[2 * size_t(index)] = -1 - cell;
    const float* p = out.points.data() + 3 * node.first;
    for (int k = 0; k < 3; ++k) b[k] = b[3 + k] = p[k];
    for (size_t i = 1; i < node.last - node.first; ++i) {
      for (int k = 0; k < 3; ++k) {
        b[k] = std::min(b[k], p[3 * i + size_t(k)]);
        b[3 + k] = std::max(b[3 + k], p[3 * i + size_t(k)]);
      }
    }
    return index;
  }
  int left = flatten(*node.child[0], level + 1, out);
  int right = flatten(*node.child[1], level + 1, out);
  out.node_children[2 * size_t(index)] = left;
  out.node_children[2 * size_t(index) + 1] = right;
  b = &out.node_bounds[6 * size_t(index)];  // the arrays may have grown
  for (int k = 0; k < 3; ++k) {
    b[k] = std::min(out.node_bounds[6 * size_t(left) + size_t(k)], out.node_bounds[6 * size_t(right) + size_t(k)]);
    b[3 + k] =
        std::max(out.node_bounds[6 * size_t(left) + 3 + size_t(k)], out.node_bounds[6 * size_t(right) + 3 + size_t(k)]);
  }
  return index;
}

void count_nodes(const BuildNode& node, size_t& nodes, size_t& leaves) {
  nodes += 1;
  if (node.is_leaf()) {
    leaves += 1;
    return;
  }
  count_nodes(*node.child[0], nodes, leaves);
  count_nodes(*node.child[1], nodes, leaves);
}

//! Squared distance from q to its second nearest point in the cells (the
//! nearest other than q itself when q is one of them), exact: what a
//! nanoflann k-nearest search for 2 gives, in the same float arithmetic.
float second_nearest_distance2(const CellTree& cells, const Eigen::Vector3f& q) {
  auto box_distance2 = [&](int node) {
    const float* b = &cells.node_bounds[6 * size_t(node)];
    float box = 0;
    for (int k = 0; k < 3; ++k) {
      float d = std::max({b[k] - q[k], 0.0f, q[k] - b[3 + k]});
      box += d * d;
    }
    return box;
  };
  float best[2] = {std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity()};
  std::vector<std::pair<float, int>> stack = {{0.0f, 0}};  // nearer halves on top
  while (!stack.empty()) {
    auto [box, node] = stack.back();
    stack.pop_back();
    if (box > best[1]) continue;
    int left = cells.node_children[2 * size_t(node)];
    if (left >= 0) {
      int right = cells.node_children[2 * size_t(node) + 1];
      float to_left = box_distance2(left), to_right = box_distance2(right);
      if (to_left <= to_right) {
        stack.emplace_back(to_right, right);
        stack.emplace_back(to_left, left);
      } else {
        stack.emplace_back(to_left, left);
        stack.emplace_back(to_right, right);
      }
      continue;
    }
    int cell = -1 - left;
    for (uint32_t p = cells.cell_offsets[size_t(cell)]; p < cells.cell_offsets[size_t(cell) + 1]; ++p) {
      const float* x = &cells.points[3 * size_t(p)];
      float d0 = x[0] - q[0], d1 = x[1] - q[1], d2 = x[2] - q[2];
      float d = d0 * d0 + d1 * d1 + d2 * d2;
      if (d < best[0]) {
        best[1] = best[0];
        best[0] = d;
      } else if (d < best[1]) {
        best[1] = d;
      }
    }
  }
  return best[1];
}

}  // namespace

size_t CellTree::byte_size() const {
  return points.size() * 4 + cell_offsets.size() * 4 + cell_centroids.size() * 4 + cell_normals.size() * 4 +
         cell_facing.size() * 4 + node_bounds.size() * 4 + node_children.size() * 4;
}

namespace {

//! The padding less four units in the last place of the largest bound: a
//! padded bound b - p, shrunk again by the inset (both rounded to floats),
//! stays outside the tight bound b.
float bounds_inset(const std::vector<float>& node_bounds, float padding) {
  float largest = 0;
  for (float b : node_bounds) largest = std::max(largest, std::fabs(b));
  float ulp = std::nextafter(largest, std::numeric_limits<float>::infinity()) - largest;
  return std::max(0.0f, padding - 4 * ulp);
}

}  // namespace

CellTree build_cell_tree(const PointCloud& cloud, size_t leaf_size, bool pad_boxes, bool split_wide_leaves,
                         const LongestLeaf& longest_leaf) {
  if (cloud.empty()) throw InputError("cannot build cells: the point cloud is empty");
  if (cloud.size() >= size_t(UINT32_MAX)) throw UnsupportedError("clouds of 2^32 points or more are not supported");
  CellTree cells;
  cells.points.assign(cloud.data(), cloud.data() + 3 * cloud.size());
  std::unique_ptr<BuildNode> root =
      CellTreeBuilder(cells.points, std::max<size_t>(leaf_size, 1), longest_leaf).build(split_wide_leaves);
  // Exact sizes up front: grown by doubling, the arrays of a 10^7-point
  // cloud would hold up to twice their size, and copy it at every step.
  size_t nodes = 0, leaves = 0;
  count_nodes(*root, nodes, leaves);
  cells.cell_offsets.reserve(leaves + 1);
  cells.node_bounds.reserve(6 * nodes);
  cells.node_children.reserve(2 * nodes);
  cells.cell_offsets.push_back(0);
  flatten(*root, 0, cells);
  root.reset();
  if (cells.depth > MCQ_MAX_TREE_DEPTH)
    throw UnsupportedError("the cell tree is " + std::to_string(cells.depth) + " levels deep, more than the " +
                           std::to_string(MCQ_MAX_TREE_DEPTH) + " the traversal supports (many duplicate points?)");
  cells.cell_centroids.resize(3 * leaves);
  cells.cell_normals.resize(3 * leaves);
  cells.cell_facing.assign(3 * leaves, 0.0f);  // no scan normals yet: every cell faces every way
#pragma omp parallel for schedule(dynamic, 256)
  for (long c = 0; c < long(leaves); ++c) {
    uint32_t first = cells.cell_offsets[size_t(c)], last = cells.cell_offsets[size_t(c) + 1];
    fit_cell_plane(cells.points.data() + 3 * size_t(first), last - first, &cells.cell_centroids[3 * size_t(c)],
                   &cells.cell_normals[3 * size_t(c)]);
  }
  cells.point_spacing = neighbour_spacing_quantile(
      cloud.points, [&](const Eigen::Vector3f& p) { return second_nearest_distance2(cells, p); }, 0.5);
  // Leaf boxes padded by the typical point spacing: tight boxes of
  // neighbouring patches of a surface leave gaps a ray can slip through,
  // and a vertex whose rays all slip through never moves; the padding
  // closes the gaps (docs/DESIGN.md). An inner box, the union of its
  // children's, grows by the same amount.
  const float padding = pad_boxes ? float(cells.point_spacing) : 0.0f;
  for (size_t node = 0; node < cells.node_count(); ++node) {
    for (int k = 0; k < 3; ++k) {
      cells.node_bounds[6 * node + size_t(k)] -= padding;
      cells.node_bounds[6 * node + 3 + size_t(k)] += padding;
    }
  }
  cells.bounds_inset = bounds_inset(cells.node_bounds, padding);
  return cells;
}

double mean_vertex_error(const CellTree& cells, const std::vector<float>& positions, std::vector<int>* nearest_cells) {
  const device::mcq_cells view = cells_view(cells);
  const size_t vertices = positions.size() / 3;
  if (nearest_cells) nearest_cells->resize(vertices, -1);
  // Each vertex's error on any core, then summed in vertex order: the same
  // bits on every run and every machine.
  std::vector<float> errors(vertices);
#pragma omp parallel for schedule(static) if (vertices > 1024)
  for (long v = 0; v < long(vertices); ++v) {
    int nearest_cell = nearest_cells ? (*nearest_cells)[size_t(v)] : -1;
    errors[size_t(v)] = device::mcq_vertex_error(view, device::mcq_load3(positions.data(), uint32_t(v)), &nearest_cell);
    if (nearest_cells) (*nearest_cells)[size_t(v)] = nearest_cell;
  }
  double sum = 0;
  for (float e : errors) sum += e;
  return vertices ? sum / double(vertices) : 0.0;
}

}  // namespace mcquad
