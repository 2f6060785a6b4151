#include <gtest/gtest.h>

#include <array>
#include <limits>

#include <nanoflann.hpp>
#include <numeric>
#include <random>

#include "cells/cell_tree.h"
#include "generate/shapes.h"
#include "core/point_index.h"
#include "core/shared_math.h"

namespace mcquad {
namespace {

PointCloud random_cloud(size_t n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  PointCloud cloud;
  for (size_t i = 0; i < n; ++i) cloud.points.emplace_back(u(random), u(random), 0.3f * u(random));
  return cloud;
}

//! A cloud with what makes splits tie: duplicate points, points sharing a
//! coordinate, a flat patch, and a cluster far away.
PointCloud awkward_cloud(size_t n, unsigned seed) {
  PointCloud cloud = random_cloud(n, seed);
  std::mt19937 random(seed + 1);
  std::uniform_int_distribution<size_t> pick(0, n - 1);
  for (size_t i = 0; i < n / 10; ++i) cloud.points.push_back(cloud.points[pick(random)]);
  for (size_t i = 0; i < n / 10; ++i) cloud.points[pick(random)].x() = 0.25f;
  for (size_t i = 0; i < n / 20; ++i) cloud.points.emplace_back(0.5f, float(i % 7) * 0.01f, float(i % 5) * 0.01f);
  for (size_t i = 0; i < 40; ++i) cloud.points.emplace_back(9.0f, 9.0f + 0.001f * float(i), 9.0f);
  return cloud;
}

device::mcq_vec3 vec(const Eigen::Vector3f& v) { return device::mcq_make_vec3(v.x(), v.y(), v.z()); }

// The order is that of the points' 13-bit-per-axis Morton codes, ties in
// input order: the bucketed sort against a plain stable sort by code.
TEST(PointCloud, SpatialSortIsAStableSortByMortonCode) {
  for (size_t n : {2u, 1000u, 70000u}) {
    PointCloud cloud = awkward_cloud(n, unsigned(n) + 5);
    cloud.normals.resize(cloud.size());
    for (size_t i = 0; i < cloud.size(); ++i) cloud.normals[i] = Eigen::Vector3f(float(i), 0, 0);
    auto [lo, hi] = bounding_box(cloud);
    Eigen::Vector3f scale = (hi - lo).cwiseMax(1e-30f).cwiseInverse() * float((1 << 13) - 1);
    auto code = [&](const Eigen::Vector3f& p) {
      Eigen::Vector3f c = (p - lo).cwiseProduct(scale);
      uint64_t key = 0;
      for (int bit = 12; bit >= 0; --bit)
        for (int k = 2; k >= 0; --k) key = key << 1 | ((uint64_t(c[k]) >> bit) & 1);
      return key;
    };
    std::vector<size_t> order(cloud.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return code(cloud.points[a]) < code(cloud.points[b]); });
    PointCloud sorted = cloud;
    sort_spatially(sorted);
    for (size_t i = 0; i < order.size(); ++i) {
      ASSERT_EQ(sorted.points[i], cloud.points[order[i]]) << n << " points, place " << i;
      ASSERT_EQ(sorted.normals[i], cloud.normals[order[i]]) << n << " points, place " << i;
    }
  }
}

TEST(PointCloud, SpatialSortIsAPermutationThatBringsNeighboursTogether) {
  PointCloud cloud = random_cloud(20000, 21);
  PointCloud sorted = cloud;
  sort_spatially(sorted);
  auto key = [](const Eigen::Vector3f& p) { return std::make_tuple(p.x(), p.y(), p.z()); };
  std::vector<std::tuple<float, float, float>> a, b;
  for (const auto& p : cloud.points) a.push_back(key(p));
  for (const auto& p : sorted.points) b.push_back(key(p));
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  EXPECT_EQ(a, b);
  auto mean_step = [](const PointCloud& c) {
    double sum = 0;
    for (size_t i = 1; i < c.size(); ++i) sum += (c.points[i] - c.points[i - 1]).norm();
    return sum / double(c.size() - 1);
  };
  EXPECT_LT(mean_step(sorted), 0.1 * mean_step(cloud));
}

struct NanoflannAdaptor {
  const std::vector<Eigen::Vector3f>& points;
  size_t kdtree_get_point_count() const { return points.size(); }
  float kdtree_get_pt(size_t i, size_t dim) const { return points[i][long(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

// The cells are nanoflann's kd-tree (build_cell_tree repeats its steps on the
// points themselves): the same leaves, each with its points in the same order,
// and the same spacing as a nanoflann 2-nearest search.
TEST(CellTree, CellsAreTheLeavesOfNanoflannsTree) {
  using Adaptor = NanoflannAdaptor;
  using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3, uint32_t>;
  for (auto [n, leaf] : {std::pair<size_t, size_t>{1, 6}, {50, 6}, {3000, 6}, {20000, 16}, {150000, 30}}) {
    PointCloud cloud = awkward_cloud(n, unsigned(n));
    Adaptor adaptor{cloud.points};
    Tree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(leaf));
    tree.buildIndex();
    std::vector<float> expected_points;
    std::vector<uint32_t> expected_offsets = {0};
    std::vector<const Tree::Node*> stack = {tree.root_node};
    while (!stack.empty()) {
      const Tree::Node* node = stack.back();
      stack.pop_back();
      if (node->child1) {
        stack.push_back(node->child2);
        stack.push_back(node->child1);
        continue;
      }
      for (size_t i = node->node_type.lr.left; i < node->node_type.lr.right; ++i)
        expected_points.insert(expected_points.end(), cloud.points[tree.vAcc[i]].data(),
                               cloud.points[tree.vAcc[i]].data() + 3);
      expected_offsets.push_back(uint32_t(node->node_type.lr.right));
    }
    CellTree cells = build_cell_tree(cloud, leaf, true, false);
    EXPECT_EQ(cells.points, expected_points) << n << " points";
    EXPECT_EQ(cells.cell_offsets, expected_offsets) << n << " points";
    EXPECT_EQ(cells.point_spacing, PointIndex<float>(cloud.points).median_spacing()) << n << " points";
  }
}

//! The longest side of the box round each cell's points.
std::vector<float> cell_spans(const CellTree& cells) {
  std::vector<float> spans;
  for (size_t c = 0; c < cells.cell_count(); ++c) {
    Eigen::AlignedBox3f box;
    for (uint32_t i = cells.cell_offsets[c]; i < cells.cell_offsets[c + 1]; ++i)
      box.extend(Eigen::Vector3f(cells.points[3 * i], cells.points[3 * i + 1], cells.points[3 * i + 2]));
    spans.push_back(box.sizes().maxCoeff());
  }
  return spans;
}

//! A leaf of the middle split can hold a few points of two tubes' walls and
//! span the air between them: random tree 5 (30,000 points) has one over
//! ten median leaves long, which drew the crease between its limbs a
//! radius out. No cell is longer than six median leaves now, and
//! the cells still hold every point once.
TEST(CellTree, NoCellSpansTheGapBetweenTwoWalls) {
  ShapeOptions options;
  options.points = 30000;
  options.seed = 5;
  const PointCloud cloud = generate_shape("random-tree", options).cloud;
  auto longest_over_median = [](std::vector<float> spans) {
    float longest = *std::max_element(spans.begin(), spans.end());
    std::nth_element(spans.begin(), spans.begin() + long(spans.size() / 2), spans.end());
    return longest / spans[spans.size() / 2];
  };
  EXPECT_GT(longest_over_median(cell_spans(build_cell_tree(cloud, 6, true, false))), 10.0f);
  const CellTree cells = build_cell_tree(cloud, 6);
  EXPECT_LE(longest_over_median(cell_spans(cells)), 6.0f);
  EXPECT_EQ(cells.cell_offsets.back(), cloud.size());
  const std::vector<float> cloud_xyz(cloud.data(), cloud.data() + 3 * cloud.size());
  auto by_point = [](const std::vector<float>& xyz) {
    std::vector<std::array<float, 3>> p(xyz.size() / 3);
    for (size_t i = 0; i < p.size(); ++i) p[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
    std::sort(p.begin(), p.end());
    return p;
  };
  EXPECT_EQ(by_point(cells.points), by_point(cloud_xyz));
}

//! With a longest leaf given (the pipeline gives half the local tube
//! radius, cells/skeleton_regions.h), every cell of two points or more is
//! no longer than it where it applies, here where x > 0 (judged at the
//! leaf's centre before it is split, so cells near x = 0 are left out), and
//! the cells still hold every point once.
TEST(CellTree, NoCellIsLongerThanTheLongestLeafGiven) {
  ShapeOptions options;
  options.points = 30000;
  options.seed = 5;
  const PointCloud cloud = generate_shape("random-tree", options).cloud;
  std::vector<float> spans = cell_spans(build_cell_tree(cloud, 6));
  std::nth_element(spans.begin(), spans.begin() + long(spans.size() / 2), spans.end());
  const float longest = spans[spans.size() / 2];
  auto limit = [longest](const Eigen::Vector3f& centre) {
    return centre.x() > 0 ? longest : std::numeric_limits<float>::infinity();
  };
  const CellTree cells = build_cell_tree(cloud, 6, true, true, limit);
  size_t split_side = 0, longer_elsewhere = 0;
  for (size_t c = 0; c < cells.cell_count(); ++c) {
    Eigen::AlignedBox3f box;
    for (uint32_t i = cells.cell_offsets[c]; i < cells.cell_offsets[c + 1]; ++i)
      box.extend(Eigen::Vector3f(cells.points[3 * i], cells.points[3 * i + 1], cells.points[3 * i + 2]));
    if (box.center().x() > 0.5f) {
      EXPECT_LE(box.sizes().maxCoeff(), longest) << "cell " << c;
      ++split_side;
    } else if (box.center().x() < -0.5f && box.sizes().maxCoeff() > longest) {
      ++longer_elsewhere;
    }
  }
  EXPECT_GT(split_side, 0u);
  EXPECT_GT(longer_elsewhere, 0u) << "the other side keeps its cells";
  EXPECT_EQ(cells.cell_offsets.back(), cloud.size());
}

TEST(CellTree, CellsPartitionTheCloudWithTightBoxes) {
  for (size_t n : {1u, 7u, 100u, 5000u}) {
    PointCloud cloud = random_cloud(n, 1);
    CellTree cells = build_cell_tree(cloud, 16);
    ASSERT_EQ(cells.point_count(), n);
    // The cells hold every point once: the same multiset as the cloud.
    auto less = [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
      return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
    };
    std::vector<Eigen::Vector3f> original = cloud.points, reordered;
    for (size_t p = 0; p < n; ++p) reordered.emplace_back(&cells.points[3 * p]);
    std::sort(original.begin(), original.end(), less);
    std::sort(reordered.begin(), reordered.end(), less);
    EXPECT_EQ(original, reordered);
    for (size_t c = 0; c < cells.cell_count(); ++c) {
      EXPECT_LE(cells.cell_offsets[c + 1] - cells.cell_offsets[c], 16u);
      EXPECT_GT(cells.cell_offsets[c + 1], cells.cell_offsets[c]);
    }
    for (size_t node = 0; node < cells.node_count(); ++node) {
      int left = cells.node_children[2 * node];
      if (left >= 0) continue;
      int cell = -1 - left;
      const float* b = &cells.node_bounds[6 * node];
      for (uint32_t p = cells.cell_offsets[cell]; p < cells.cell_offsets[cell + 1]; ++p)
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(cells.points[3 * p + k], b[k]);
          EXPECT_LE(cells.points[3 * p + k], b[3 + k]);
        }
    }
  }
}

TEST(CellTree, PlaneNormalsOfPointsDrawnFromKnownPlanes) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> u(-1, 1);
  Eigen::Vector3f normal = Eigen::Vector3f(1, 2, 3).normalized();
  Eigen::Vector3f a = normal.unitOrthogonal(), b = normal.cross(a);
  PointCloud cloud;
  for (int i = 0; i < 4000; ++i) cloud.points.push_back(Eigen::Vector3f(0.5f, 0, 1) + u(random) * a + u(random) * b);
  CellTree cells = build_cell_tree(cloud, 20);
  for (size_t c = 0; c < cells.cell_count(); ++c) {
    // A plane needs three points; nanoflann's middle split leaves a few
    // smaller cells, whose normal is arbitrary.
    if (cells.cell_offsets[c + 1] - cells.cell_offsets[c] < 3) continue;
    Eigen::Vector3f t(&cells.cell_normals[3 * c]);
    EXPECT_NEAR(std::abs(t.dot(normal)), 1.0f, 1e-3f);
  }
}

//! The nearest-point search prunes on the padded boxes shrunk by
//! bounds_inset; it must still find the brute-force answer (the lowest index
//! among equally near points), near the surface where the padding matters and
//! far from the origin where the padding's rounding does.
class NearestPointCell : public ::testing::TestWithParam<float> {};

TEST_P(NearestPointCell, MatchesBruteForce) {
  const Eigen::Vector3f offset = Eigen::Vector3f::Constant(GetParam());
  PointCloud cloud = awkward_cloud(3000, 5);
  for (auto& p : cloud.points) p += offset;
  CellTree cells = build_cell_tree(cloud, 12);
  ASSERT_GT(cells.bounds_inset, 0.0f);
  ASSERT_LT(cells.bounds_inset, float(cells.point_spacing));
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(-1.5, 1.5), near(-0.02f, 0.02f);
  std::uniform_int_distribution<size_t> pick(0, cells.point_count() - 1);
  for (int q = 0; q < 600; ++q) {
    Eigen::Vector3f query = q % 2 ? offset + Eigen::Vector3f(u(random), u(random), u(random))
                                  : Eigen::Vector3f(&cells.points[3 * pick(random)]) +
                                        Eigen::Vector3f(near(random), near(random), near(random));
    float best = INFINITY;
    size_t best_point = 0;
    for (size_t p = 0; p < cells.point_count(); ++p) {
      float d2 = device::mcq_dot(device::mcq_sub(device::mcq_load3(cells.points.data(), uint32_t(p)), vec(query)),
                                 device::mcq_sub(device::mcq_load3(cells.points.data(), uint32_t(p)), vec(query)));
      if (d2 < best) best = d2, best_point = p;
    }
    float d2;
    int cell =
        device::mcq_nearest_point_cell(cells.node_bounds.data(), cells.node_children.data(), cells.cell_offsets.data(),
                                       cells.points.data(), cells.bounds_inset, vec(query), -1, &d2);
    ASSERT_GE(cell, 0);
    EXPECT_EQ(d2, best);
    EXPECT_LE(cells.cell_offsets[size_t(cell)], best_point);
    EXPECT_GT(cells.cell_offsets[size_t(cell) + 1], best_point);
    // A guess (the evolution's last answer for the vertex) changes only how
    // fast: the same cell and distance from any cell, the answer included.
    std::uniform_int_distribution<int> any_cell(0, int(cells.cell_count()) - 1);
    for (int guess : {cell, any_cell(random), std::max(0, cell - 1)}) {
      float guessed_d2;
      EXPECT_EQ(device::mcq_nearest_point_cell(cells.node_bounds.data(), cells.node_children.data(),
                                               cells.cell_offsets.data(), cells.points.data(), cells.bounds_inset,
                                               vec(query), guess, &guessed_d2),
                cell);
      EXPECT_EQ(guessed_d2, d2);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Offsets, NearestPointCell, ::testing::Values(0.0f, 3000.0f, -70000.0f));

struct Hit {
  int cell = -1;
  float entry = -1;
};

//! Brute force: the leaf box entered first within reach, ties to the lower
//! cell (the rule of mcq_hit_is_better); cell -1 when none.
//! Cells labelled with one of five bones, cell % 5, of which the filter
//! sees bones 1 and 3: the traversals must pass through the others.
struct BoneLabels {
  std::vector<uint32_t> cell_bones, visible{1, 3};
  explicit BoneLabels(const CellTree& cells) {
    for (size_t c = 0; c < cells.cell_count(); ++c) cell_bones.push_back(uint32_t(c % 5));
  }
  device::mcq_cell_filter filter(bool on) const {
    device::mcq_cell_filter f = device::mcq_no_cell_filter();
    if (on) {
      f.cell_bones = cell_bones.data();
      f.visible = visible.data();
      f.count = uint32_t(visible.size());
    }
    return f;
  }
};

Hit first_hit_brute_force(const CellTree& cells, const Eigen::Vector3f& o, const Eigen::Vector3f& d, float reach,
                          device::mcq_cell_filter filter) {
  Hit best;
  device::mcq_vec3 inv = device::mcq_inverse_direction(vec(d));
  for (size_t node = 0; node < cells.node_count(); ++node) {
    int child = cells.node_children[2 * node];
    if (child >= 0) continue;
    int cell = -1 - child;
    float t = device::mcq_ray_box_entry(cells.node_bounds.data(), int(node), vec(o), inv);
    if (t < 0 || t > reach || !device::mcq_cell_is_visible(filter, cell)) continue;
    if (best.cell < 0 || t < best.entry || (t == best.entry && cell < best.cell)) best = {cell, t};
  }
  return best;
}

TEST(CellTree, FirstCellHitMatchesBruteForce) {
  PointCloud cloud = random_cloud(4000, 11);
  CellTree cells = build_cell_tree(cloud, 16);
  std::mt19937 random(13);
  std::uniform_real_distribution<float> u(-2, 2);
  BoneLabels labels(cells);
  int hits = 0, ties = 0, filtered_hits = 0;
  for (int q = 0; q < 500; ++q) {
    device::mcq_cell_filter filter = labels.filter(q % 4 == 1);
    Eigen::Vector3f o(u(random), u(random), u(random));
    if (q % 3 == 0) o = cloud.points[size_t(q)];  // inside several padded boxes
    Eigen::Vector3f d = Eigen::Vector3f(u(random), u(random), u(random)).normalized();
    if (q % 10 == 0) d = Eigen::Vector3f::UnitX();  // axis-parallel rays
    float reach = q % 2 ? 1.0f : 10.0f;
    float entry;
    int cell = device::mcq_first_cell_hit(cells.node_bounds.data(), cells.node_children.data(), filter, vec(o), vec(d),
                                          reach, &entry);
    Hit expected = first_hit_brute_force(cells, o, d, reach, filter);
    ASSERT_EQ(cell, expected.cell) << "ray " << q;
    if (cell < 0) continue;
    EXPECT_EQ(entry, expected.entry);
    hits += 1;
    ties += expected.entry == 0;
    if (filter.count > 0) {
      filtered_hits += 1;
      EXPECT_TRUE(cell % 5 == 1 || cell % 5 == 3) << "ray " << q << " hit an invisible cell";
    }
  }
  EXPECT_GT(filtered_hits, 20);
  EXPECT_GT(hits, 150);  // the cloud is a thin slab: many random rays miss it
  EXPECT_GT(ties, 100);  // origins on the cloud sit in several boxes at once
}

TEST(CellTree, PacketTraversalGivesEachRayItsOwnFirstHit) {
  PointCloud cloud = random_cloud(4000, 17);
  CellTree cells = build_cell_tree(cloud, 6);
  std::mt19937 random(19);
  std::uniform_real_distribution<float> u(-1, 1);
  BoneLabels labels(cells);
  int banded_rays = 0, multi_cell_bands = 0;
  for (int q = 0; q < 200; ++q) {
    device::mcq_cell_filter filter = labels.filter(q % 4 == 3);
    Eigen::Vector3f o = q % 2 ? cloud.points[size_t(q)] : Eigen::Vector3f(u(random), u(random), 0.3f * u(random));
    Eigen::Vector3f axis = Eigen::Vector3f(u(random), u(random), u(random)).normalized();
    int count = 1 + q % MCQ_PACKET_SIZE;
    float x[MCQ_PACKET_SIZE], y[MCQ_PACKET_SIZE], z[MCQ_PACKET_SIZE], entries[MCQ_PACKET_SIZE];
    int hit_cells[MCQ_PACKET_SIZE];
    for (int r = 0; r < count; ++r) {  // a narrow cone, as a vertex casts, with some stray rays
      float spread = r % 7 == 6 ? 2.0f : 0.3f;
      Eigen::Vector3f d = (axis + spread * Eigen::Vector3f(u(random), u(random), u(random))).normalized();
      x[r] = d.x(), y[r] = d.y(), z[r] = d.z();
    }
    float reach = q % 3 ? 0.2f : 5.0f;
    // Half the packets also gather their rays' bands, which must not change
    // the first hits.
    float band = q % 2 ? 0.0f : 0.05f;
    int leaves[MCQ_BAND_CANDIDATES], candidates = -1;
    device::mcq_first_cell_hits(cells.node_bounds.data(), cells.node_children.data(), filter, vec(o), x, y, z, count,
                                reach, band, hit_cells, entries, leaves, &candidates);
    ASSERT_LT(candidates, MCQ_BAND_CANDIDATES) << "packet " << q << ": the candidates overflowed";
    for (int r = 0; r < count; ++r) {
      float entry;
      device::mcq_vec3 dir = device::mcq_make_vec3(x[r], y[r], z[r]);
      int cell = device::mcq_first_cell_hit(cells.node_bounds.data(), cells.node_children.data(), filter, vec(o), dir,
                                            reach, &entry);
      ASSERT_EQ(hit_cells[r], cell) << "packet " << q << " ray " << r;
      if (cell >= 0) {
        EXPECT_EQ(entries[r], entry);
      }
      if (cell < 0 || band == 0.0f) continue;
      // Each ray's band from the packet's candidates, against the single-ray walk.
      int packet_band[MCQ_BAND_CELLS], single_band[MCQ_BAND_CELLS];
      int in_packet = device::mcq_band_of_ray(cells.node_bounds.data(), cells.node_children.data(), leaves, candidates,
                                              vec(o), dir, entry, band, packet_band);
      int in_single = device::mcq_cells_in_band(cells.node_bounds.data(), cells.node_children.data(), filter, vec(o),
                                                dir, entry, band, single_band);
      ASSERT_EQ(in_packet, in_single) << "packet " << q << " ray " << r;
      ASSERT_GE(in_single, 1);
      EXPECT_NE(std::find(single_band, single_band + in_single, cell), single_band + in_single)
          << "the first hit is in its band";
      for (int k = 0; k < in_single; ++k) EXPECT_EQ(packet_band[k], single_band[k]);
      banded_rays += 1;
      multi_cell_bands += in_single > 1;
    }
  }
  EXPECT_GT(banded_rays, 200);
  EXPECT_GT(multi_cell_bands, 50);
}

//! Brute force of mcq_cells_in_band: every visible leaf whose box the line
//! crosses within band of center, sorted by (gap, cell), the first
//! MCQ_BAND_CELLS.
std::vector<int> band_brute_force(const CellTree& cells, const Eigen::Vector3f& o, const Eigen::Vector3f& d,
                                  float center, float band, device::mcq_cell_filter filter) {
  device::mcq_vec3 inv = device::mcq_inverse_direction(vec(d));
  std::vector<std::pair<float, int>> found;
  for (size_t node = 0; node < cells.node_count(); ++node) {
    int child = cells.node_children[2 * node];
    if (child >= 0 || !device::mcq_cell_is_visible(filter, -1 - child)) continue;
    float gap = device::mcq_line_box_gap(cells.node_bounds.data(), int(node), vec(o), inv, center);
    if (gap <= band) found.emplace_back(gap, -1 - child);
  }
  std::sort(found.begin(), found.end());
  std::vector<int> result;
  for (size_t k = 0; k < found.size() && k < MCQ_BAND_CELLS; ++k) result.push_back(found[k].second);
  return result;
}

TEST(CellTree, CellsInBandMatchBruteForceBehindTheOriginToo) {
  PointCloud cloud = random_cloud(4000, 23);
  CellTree cells = build_cell_tree(cloud, 6);
  std::mt19937 random(29);
  std::uniform_real_distribution<float> u(-1, 1);
  BoneLabels labels(cells);
  int behind = 0, full = 0;
  for (int q = 0; q < 300; ++q) {
    device::mcq_cell_filter filter = labels.filter(q % 3 == 1);
    Eigen::Vector3f o = cloud.points[size_t(q)];
    Eigen::Vector3f d = Eigen::Vector3f(u(random), u(random), u(random)).normalized();
    float center = q % 2 ? 0.0f : 0.05f, band = q % 5 == 0 ? 0.5f : 0.08f;
    int band_cells[MCQ_BAND_CELLS];
    int count = device::mcq_cells_in_band(cells.node_bounds.data(), cells.node_children.data(), filter, vec(o), vec(d),
                                          center, band, band_cells);
    std::vector<int> expected = band_brute_force(cells, o, d, center, band, filter);
    ASSERT_EQ(std::vector<int>(band_cells, band_cells + count), expected) << "ray " << q;
    full += count == MCQ_BAND_CELLS;
    device::mcq_vec3 inv = device::mcq_inverse_direction(vec(d));
    for (size_t node = 0; node < cells.node_count(); ++node) {
      int child = cells.node_children[2 * node];
      if (child >= 0) continue;
      float t_enter, t_exit;
      const float* b = &cells.node_bounds[6 * node];
      bool crosses = device::mcq_line_box_interval(device::mcq_make_vec3(b[0] - o.x(), b[1] - o.y(), b[2] - o.z()),
                                                   device::mcq_make_vec3(b[3] - o.x(), b[4] - o.y(), b[5] - o.z()), inv,
                                                   &t_enter, &t_exit);
      // A cell wholly behind the origin, in the band: the half-line never sees it.
      if (crosses && t_exit < 0 && std::find(band_cells, band_cells + count, -1 - child) != band_cells + count)
        behind += 1;
    }
  }
  EXPECT_GT(behind, 50);
  EXPECT_GT(full, 5);  // wide bands overflow, and keep the cells nearest the center
}

}  // namespace
}  // namespace mcquad
