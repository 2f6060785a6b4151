#include "cells/cell_facing.h"

#include "core/point_index.h"

namespace mcquad {
namespace {

//! Scan normals averaged per cell: enough to outvote a stray one, few
//! enough to stay within a cell's neighbourhood on the densest sample.
constexpr size_t kNormalsPerCell = 8;
//! The least length of the mean of those unit normals for the cell to have
//! a facing: normals spread over 90 degrees give about 0.9; of 8 opposite
//! normals from both sides of a thin part, 7 must agree (0.75).
constexpr float kLeastAgreement = 0.7f;

}  // namespace

void orient_cells(CellTree& cells, const OrientedSample& oriented) {
  cells.cell_facing.assign(3 * cells.cell_count(), 0.0f);
  if (oriented.empty()) return;
  const PointIndex<float> index(oriented.points);
#pragma omp parallel for schedule(dynamic, 1024)
  for (long c = 0; c < long(cells.cell_count()); ++c) {
    Eigen::Vector3f centroid(&cells.cell_centroids[3 * size_t(c)]);
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    std::vector<size_t> nearest = index.k_nearest(centroid, kNormalsPerCell);
    for (size_t i : nearest) sum += oriented.normals[i];
    if (nearest.empty() || sum.norm() < kLeastAgreement * float(nearest.size())) continue;
    sum.normalize();
    for (int k = 0; k < 3; ++k) cells.cell_facing[3 * size_t(c) + size_t(k)] = sum[k];
  }
}

double facing_fraction(const CellTree& cells) {
  if (cells.cell_count() == 0) return 0;
  size_t facing = 0;
  for (size_t c = 0; c < cells.cell_count(); ++c) facing += !Eigen::Vector3f(&cells.cell_facing[3 * c]).isZero();
  return double(facing) / double(cells.cell_count());
}

}  // namespace mcquad
