#include <gtest/gtest.h>

#include "core/errors.h"
#include "generate/shapes.h"
#include "helpers.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"
#include "core/point_index.h"

namespace mcquad {
namespace {

//! The paper's figures: point counts and bounding boxes of Fig. 6 and Fig. 7.
TEST(Generate, PaperStandInsHaveThePaperCountsAndBoxes) {
  struct Case {
    const char* name;
    size_t points;
    Eigen::Vector3f lo, hi;
    float tolerance;
  } cases[] = {
      {"tube-frame", 182274, {-6.8f, -7.83f, -7.83f}, {6.8f, 7.83f, 7.0f}, 0.02f},
      // The knot's y extent is 28.145 against the paper's 28.16 (see shapes.cpp).
      {"torus-knot", 413696, {-24.88f, -17.25f, -1.71f}, {4.43f, 10.91f, 7.41f}, 0.05f},
  };
  for (const auto& c : cases) {
    GeneratedShape shape = generate_shape(c.name, {});
    EXPECT_EQ(shape.cloud.size(), c.points) << c.name;
    auto [lo, hi] = bounding_box(shape.cloud);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(lo[k], c.lo[k], c.tolerance) << c.name << " min " << k;
      EXPECT_NEAR(hi[k], c.hi[k], c.tolerance) << c.name << " max " << k;
    }
  }
}

TEST(Generate, EveryShapeSamplesItsTrueSurfaceUniformly) {
  for (const auto& [name, what] : shape_catalogue()) {
    if (std::string(name) == "torus-knot" || std::string(name) == "tube-frame") continue;  // above
    GeneratedShape shape = test::small_shape(name, 5000);
    ASSERT_EQ(shape.cloud.size(), 5000u) << name;
    for (const auto& p : shape.cloud.points)
      ASSERT_NEAR(shape.surface.signed_distance(p.cast<double>()), 0.0, 1e-4) << name;
    EXPECT_GE(shape.skeleton.edges.size(), 1u);
  }
  // Uniform by area: a straight capsule's cylinder holds its share of points.
  GeneratedShape tube = test::small_shape("tube", 20000);
  size_t on_cylinder = 0;
  for (const auto& p : tube.cloud.points) on_cylinder += std::abs(p.z()) <= 4.0f;
  double share = (2 * M_PI * 8.0) / (2 * M_PI * 8.0 + 4 * M_PI);  // length 8, radius 1
  EXPECT_NEAR(double(on_cylinder) / 20000, share, 0.01);
}

TEST(Generate, WritesCloudSkeletonAndSurfaceThatReadBack) {
  test::TempDir dir;
  GeneratedShape shape = test::small_shape("t-shape", 3000);
  write_generated_shape(shape, dir.file("out"));
  EXPECT_EQ(read_point_cloud(dir.file("out/t-shape.ply")).size(), 3000u);
  EXPECT_EQ(read_skeleton(dir.file("out/t-shape.skeleton.obj")).edges.size(), shape.skeleton.edges.size());
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/t-shape.surface.json")));
  EXPECT_EQ(shape.open_ends, 1);
  ShapeOptions noisy;
  noisy.noise = 0.05;
  GeneratedShape rough = test::small_shape("tube", 5000, noisy);
  double spread = 0;
  for (const auto& p : rough.cloud.points) spread += std::pow(rough.surface.signed_distance(p.cast<double>()), 2);
  EXPECT_NEAR(std::sqrt(spread / 5000), 0.05, 0.005) << "noise is a fraction of the radius (1 here)";
}

TEST(Generate, ScanDefectsOutliersDensityAndHoles) {
  ShapeOptions options;
  options.outliers = 0.01;
  GeneratedShape noisy = test::small_shape("t-shape", 20000, options);
  size_t off_surface = 0;
  for (const auto& p : noisy.cloud.points)
    off_surface += std::abs(noisy.surface.signed_distance(p.cast<double>())) >= 0.99;
  EXPECT_EQ(off_surface, 200u);

  // Density: the T's arms run along x, from -5 to 5.
  auto end_ratio = [](const PointCloud& cloud) {
    double left = 0, right = 0;
    for (const auto& p : cloud.points) {
      left += p.x() < -4.0f;
      right += p.x() > 4.0f;
    }
    return left / std::max(right, 1.0);
  };
  ShapeOptions uneven;
  uneven.density_ratio = 10;
  EXPECT_GT(end_ratio(test::small_shape("t-shape", 20000, uneven).cloud), 4.0);
  EXPECT_NEAR(end_ratio(test::small_shape("t-shape", 20000).cloud), 1.0, 0.15);

  // Holes: some place on the true surface is a radius from every point.
  auto largest_gap = [](const GeneratedShape& shape) {
    PointIndex<float> index(shape.cloud.points);
    std::mt19937_64 random(99);
    PointCloud probe = shape.surface.sample(4000, random, 0.0);
    double gap = 0;
    for (const auto& p : probe.points) gap = std::max(gap, std::sqrt(double(index.nearest(p).second)));
    return gap;
  };
  ShapeOptions holed;
  holed.holes = 3;
  EXPECT_GT(largest_gap(test::small_shape("torus", 20000, holed)), 0.8);
  EXPECT_LT(largest_gap(test::small_shape("torus", 20000)), 0.3);
}

// Skeletons as other tools make them: the T's nodes move by half their
// radius, across their bones; its three end nodes come a radius closer to
// the junction. The cloud and the true surface do not move.
TEST(Generate, SkeletonOffCentreAndShortOfTheTips) {
  GeneratedShape plain = test::small_shape("t-shape", 5000);
  ShapeOptions off;
  off.skeleton_offset = 0.5;
  GeneratedShape moved = test::small_shape("t-shape", 5000, off);
  ASSERT_EQ(moved.skeleton.nodes.size(), plain.skeleton.nodes.size());
  EXPECT_EQ(moved.cloud.points, plain.cloud.points);
  for (size_t v = 0; v < plain.skeleton.nodes.size(); ++v)
    EXPECT_NEAR((moved.skeleton.nodes[v] - plain.skeleton.nodes[v]).norm(), 0.5, 1e-9) << "node " << v;
  ShapeOptions short_ends;
  short_ends.short_ends = 1.0;
  GeneratedShape shortened = test::small_shape("t-shape", 5000, short_ends);
  // The T's ends: its arms reach x = -4 and 4, its leg y = -5 (radius 1).
  auto reach = [](const GeneratedShape& s, int axis, double sign) {
    double best = -1e9;
    for (const auto& p : s.skeleton.nodes) best = std::max(best, sign * p[axis]);
    return best;
  };
  EXPECT_NEAR(reach(shortened, 0, 1), 3.0, 1e-9);
  EXPECT_NEAR(reach(shortened, 0, -1), 3.0, 1e-9);
  EXPECT_NEAR(reach(shortened, 1, -1), 4.0, 1e-9);
  EXPECT_EQ(shortened.surface.capsules().size(), plain.surface.capsules().size());
}

//! The thin branch's radius and angle: the branch's capsule takes them, and
//! values outside the shape's range are refused with the reason.
TEST(Generate, ThinBranchTakesItsRadiusAndAngle) {
  ShapeOptions options;
  options.branch_radius = 0.3;
  options.angle_degrees = 90;
  GeneratedShape shape = test::small_shape("thin-branch", 5000, options);
  double smallest = 1e9;
  for (const auto& capsule : shape.surface.capsules()) smallest = std::min(smallest, capsule.radius);
  EXPECT_NEAR(smallest, 0.3, 1e-12);
  // At 90 degrees every node off the trunk's axis (x = 0) lies at y = 0.
  for (const auto& p : shape.skeleton.nodes)
    if (std::abs(p.x()) > 1e-9) {
      EXPECT_NEAR(p.y(), 0.0, 1e-9) << p.transpose();
    }
  options.branch_radius = 1.5;
  EXPECT_THROW(test::small_shape("thin-branch", 5000, options), InputError);
  options.branch_radius = 0.2;
  options.angle_degrees = 10;
  EXPECT_THROW(test::small_shape("thin-branch", 5000, options), InputError);
}

//! issue 14's fat body: one bone fewer in the skeleton than capsules in the
//! surface (the ear), and the legs' junctions inside the body.
TEST(Generate, BlobLimbsHasABonelessEarAndJunctionsInsideTheBody) {
  GeneratedShape blob = test::small_shape("blob-limbs", 5000);
  EXPECT_EQ(blob.surface.capsules().size(), blob.skeleton.edges.size() + 1);
  std::vector<int> degree(blob.skeleton.nodes.size(), 0);
  for (const auto& e : blob.skeleton.edges) ++degree[size_t(e[0])], ++degree[size_t(e[1])];
  int junctions_inside = 0;
  for (size_t v = 0; v < degree.size(); ++v)
    junctions_inside += degree[v] >= 3 && blob.surface.signed_distance(blob.skeleton.nodes[v]) < -2.0;
  EXPECT_EQ(junctions_inside, 2);
}

//! The random tree: the seed picks it (same seed, same tree; another seed,
//! another); it is a tree (no cycle) with one to three junctions of valence
//! 3 to 6, and over 20 seeds every valence from 3 to 6 comes up. That its
//! tubes meet only at their junctions shows in the initial meshes
//! (Issue20/RandomTrees.*: no crossing face pairs, the mesh outward).
TEST(Generate, RandomTreesDifferBySeedAndAreTreesOfJunctionsOfValenceThreeToSix) {
  auto tree = [](uint64_t seed) {
    ShapeOptions o;
    o.seed = seed;
    return test::small_shape("random-tree", 2000, o);
  };
  EXPECT_EQ(tree(3).skeleton.nodes, tree(3).skeleton.nodes);
  EXPECT_NE(tree(3).skeleton.nodes, tree(4).skeleton.nodes);
  int sizes[7] = {};
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    GeneratedShape shape = tree(seed);
    EXPECT_EQ(shape.independent_cycles, 0) << "seed " << seed;
    std::vector<int> degree(shape.skeleton.nodes.size(), 0);
    for (const auto& e : shape.skeleton.edges) ++degree[size_t(e[0])], ++degree[size_t(e[1])];
    int junctions = 0;
    for (int d : degree) {
      EXPECT_GE(d, 1);
      EXPECT_LE(d, 6) << "seed " << seed;
      if (d >= 3) ++sizes[d], ++junctions;
    }
    EXPECT_GE(junctions, 1);
    EXPECT_LE(junctions, 3);
  }
  for (int valence = 3; valence <= 6; ++valence) EXPECT_GT(sizes[valence], 0) << "no junction of valence " << valence;
}

}  // namespace
}  // namespace mcquad
