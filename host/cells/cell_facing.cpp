#include "cells/cell_facing.h"

#include <algorithm>

namespace mcquad {
namespace {

//! The least length of the mean of a cell's unit normals for the cell to
//! have a facing: normals spread over 90 degrees give about 0.9; a cell
//! holding both sides of a thin part, about as many normals one way as the
//! other, gives near 0.
constexpr float kLeastAgreement = 0.7f;

//! The cell holding a point that is one of the cloud's, found by walking
//! down the tree through every box that contains it (boxes of neighbours
//! overlap by their padding) to a leaf that holds the point itself; -1 when
//! no cell does (a point not in the cloud). The same cell as the nearest
//! point search (mcq_nearest_point_cell) finds, in half its time on the knot
//! (48 against 110 ms for 413,696 points): no box distances to compare.
int cell_holding(const CellTree& cells, const Eigen::Vector3f& p) {
  auto contains = [&](int node) {
    const float* b = &cells.node_bounds[6 * size_t(node)];
    return b[0] <= p.x() && p.x() <= b[3] && b[1] <= p.y() && p.y() <= b[4] && b[2] <= p.z() && p.z() <= b[5];
  };
  int stack[2 * MCQ_STACK_SIZE];
  int top = 0;
  if (contains(0)) stack[top++] = 0;
  while (top > 0) {
    int node = stack[--top];
    int left = cells.node_children[2 * size_t(node)];
    if (left < 0) {
      int cell = -1 - left;
      for (uint32_t i = cells.cell_offsets[size_t(cell)]; i < cells.cell_offsets[size_t(cell) + 1]; ++i)
        if (Eigen::Vector3f(&cells.points[3 * size_t(i)]) == p) return cell;
      continue;
    }
    int right = cells.node_children[2 * size_t(node) + 1];
    if (top + 2 > 2 * MCQ_STACK_SIZE) continue;
    if (contains(right)) stack[top++] = right;
    if (contains(left)) stack[top++] = left;
  }
  return -1;
}

}  // namespace

void orient_cells(CellTree& cells, const OrientedSample& oriented) {
  const size_t cell_count = cells.cell_count();
  cells.cell_facing.assign(3 * cell_count, 0.0f);
  if (oriented.empty()) return;
  // Where each oriented point lies, in parallel; then the sums in the
  // sample's order, so the facings come out the same on any thread count.
  std::vector<int> cell_of(oriented.points.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(oriented.points.size()); ++i)
    cell_of[size_t(i)] = cell_holding(cells, oriented.points[size_t(i)]);
  std::vector<Eigen::Vector3f> sums(cell_count, Eigen::Vector3f::Zero());
  std::vector<uint32_t> counts(cell_count, 0);
  for (size_t i = 0; i < cell_of.size(); ++i) {
    if (cell_of[i] < 0) continue;
    sums[size_t(cell_of[i])] += oriented.normals[i];
    counts[size_t(cell_of[i])] += 1;
  }
  for (size_t c = 0; c < cell_count; ++c) {
    if (counts[c] == 0 || sums[c].norm() < kLeastAgreement * float(counts[c])) continue;
    Eigen::Vector3f facing = sums[c].normalized();
    std::copy_n(facing.data(), 3, &cells.cell_facing[3 * c]);
  }
}

double facing_fraction(const CellTree& cells) {
  if (cells.cell_count() == 0) return 0;
  size_t facing = 0;
  for (size_t c = 0; c < cells.cell_count(); ++c) facing += !Eigen::Vector3f(&cells.cell_facing[3 * c]).isZero();
  return double(facing) / double(cells.cell_count());
}

}  // namespace mcquad
