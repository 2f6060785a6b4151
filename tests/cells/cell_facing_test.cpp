#include "cells/cell_facing.h"

#include <gtest/gtest.h>

#include <random>

#include "core/point_index.h"
#include "helpers.h"

namespace mcquad {
namespace {

Eigen::Vector3f facing_of(const CellTree& cells, size_t c) { return Eigen::Vector3f(&cells.cell_facing[3 * c]); }

//! A plate of `points` points on each of its two faces, z = 0 and z =
//! `thickness`, with their outward normals (-z and +z).
PointCloud two_sided_plate(int points, float thickness) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> u(-1, 1);
  PointCloud cloud;
  for (int i = 0; i < 2 * points; ++i) {
    bool top = i % 2 == 1;
    cloud.points.emplace_back(u(random), u(random), top ? thickness : 0.0f);
    cloud.normals.emplace_back(0, 0, top ? 1.0f : -1.0f);
  }
  return cloud;
}

//! On a tube, every cell faces the way the scan's normals do where it lies:
//! outward, within a few degrees of the normal of the point nearest its
//! centroid.
TEST(CellFacing, CellsOfATubeFaceOutward) {
  GeneratedShape shape = test::small_shape("tube", 20000);
  ASSERT_EQ(shape.cloud.normals.size(), shape.cloud.size());
  CellTree cells = build_cell_tree(shape.cloud, 6);
  orient_cells(cells, oriented_sample(shape.cloud));
  PointIndex<float> index(shape.cloud.points);
  size_t known = 0;
  for (size_t c = 0; c < cells.cell_count(); ++c) {
    Eigen::Vector3f f = facing_of(cells, c);
    if (f.isZero()) continue;
    ++known;
    EXPECT_NEAR(f.norm(), 1.0f, 1e-5f);
    Eigen::Vector3f centroid(&cells.cell_centroids[3 * c]);
    EXPECT_GT(f.dot(shape.cloud.normals[size_t(index.nearest(centroid).first)]), 0.95f) << "cell " << c;
  }
  EXPECT_GE(double(known), 0.99 * double(cells.cell_count()));
}

//! Without normals nothing faces anywhere, so every cell stays visible.
TEST(CellFacing, ACloudWithoutNormalsLeavesEveryCellUnknown) {
  GeneratedShape shape = test::small_shape("tube", 5000);
  CellTree cells = build_cell_tree(shape.cloud, 6);
  orient_cells(cells, OrientedSample());
  ASSERT_EQ(cells.cell_facing.size(), 3 * cells.cell_count());
  for (float x : cells.cell_facing) EXPECT_EQ(x, 0.0f);
}

//! A cell holding both sides of a part thinner than the point spacing gets
//! no facing where the sides' normals cancel, rather than a wrong one; a
//! cell holding one side faces that side's way. On a thick plate every cell
//! holds one side.
TEST(CellFacing, CellsMixingBothSidesOfAThinPlateStayUnknown) {
  for (float thickness : {0.0005f, 0.5f}) {
    PointCloud plate = two_sided_plate(4000, thickness);
    CellTree cells = build_cell_tree(plate, 6);
    orient_cells(cells, oriented_sample(plate));
    size_t mixed = 0;
    for (size_t c = 0; c < cells.cell_count(); ++c) {
      int up = 0, count = 0;
      for (uint32_t i = cells.cell_offsets[c]; i < cells.cell_offsets[c + 1]; ++i, ++count)
        up += cells.points[3 * size_t(i) + 2] > thickness / 2 ? 1 : -1;
      Eigen::Vector3f f = facing_of(cells, c);
      if (std::abs(up) < 0.7 * count) {
        ++mixed;
        EXPECT_TRUE(f.isZero()) << "thickness " << thickness << " cell " << c;
      } else {
        EXPECT_GT(f.z() * float(up), 0.99f) << "thickness " << thickness << " cell " << c;
      }
    }
    if (thickness < 0.01f)
      EXPECT_GE(double(mixed), 0.5 * double(cells.cell_count())) << "the plate's sides share most cells";
    else
      EXPECT_EQ(mixed, 0u);
  }
}

//! The filter the rays use: a cell turned away from the vertex by more than
//! the angle min_facing allows is passed through; one with no facing never.
TEST(CellFacing, RaysPassThroughCellsThatFaceAway) {
  const float facing[] = {0, 0, 1, 0, 0, 0};  // cell 0 faces +z, cell 1 is unknown
  device::mcq_cell_filter filter = device::mcq_no_cell_filter();
  filter.facing = facing;
  filter.min_facing = 0.5f;  // within 60 degrees
  auto visible_from = [&](Eigen::Vector3f n, int cell) {
    filter.normal = device::mcq_make_vec3(n.x(), n.y(), n.z());
    return device::mcq_cell_is_visible(filter, cell) != 0;
  };
  EXPECT_TRUE(visible_from({0, 0, 1}, 0));
  EXPECT_TRUE(visible_from(Eigen::Vector3f(1, 0, 1).normalized(), 0));   // 45 degrees
  EXPECT_FALSE(visible_from(Eigen::Vector3f(2, 0, 1).normalized(), 0));  // 63 degrees
  EXPECT_FALSE(visible_from({0, 0, -1}, 0));
  for (Eigen::Vector3f n : {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(0, 0, -1), Eigen::Vector3f(1, 0, 0)})
    EXPECT_TRUE(visible_from(n, 1));
}

}  // namespace
}  // namespace mcquad
