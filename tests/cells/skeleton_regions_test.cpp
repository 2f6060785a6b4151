#include <gtest/gtest.h>

#include <algorithm>

#include "cells/skeleton_regions.h"
#include "helpers.h"
#include "pipeline/fit.h"
#include "pipeline/prepare.h"

namespace mcquad {
namespace {

struct Prepared {
  GeneratedShape shape;
  SkeletonGraph graph;
  EvolutionSetup setup;
  explicit Prepared(const std::string& name, size_t points = 20000)
      : shape(test::small_shape(name, points)),
        graph(build_skeleton_graph(shape.skeleton, name)),
        setup(prepare_evolution(graph, shape.cloud, {}, FitOptions().leaf_size, name)) {}

  const SkeletonRegions& regions() const { return setup.regions; }
  bool sees(uint32_t vertex, uint32_t cell) const {
    const SkeletonRegions& r = regions();
    uint32_t bone = r.vertex_bones[vertex];
    auto first = r.visible_bones.begin() + r.visible_offsets[bone],
         last = r.visible_bones.begin() + r.visible_offsets[bone + 1];
    return std::binary_search(first, last, r.cell_bones[cell]);
  }
  Eigen::Vector3d vertex(uint32_t v) const {
    const float* p = &setup.arrays.positions[3 * size_t(v)];
    return {p[0], p[1], p[2]};
  }
  Eigen::Vector3d centroid(uint32_t c) const {
    const float* p = &setup.cells.cell_centroids[3 * size_t(c)];
    return {p[0], p[1], p[2]};
  }
  uint32_t nearest_cell(uint32_t v) const {
    uint32_t best = 0;
    for (uint32_t c = 1; c < setup.cells.cell_count(); ++c)
      if ((centroid(c) - vertex(v)).squaredNorm() < (centroid(best) - vertex(v)).squaredNorm()) best = c;
    return best;
  }
  //! Fraction of (every 7th) vertex whose nearest cell it may see: its own
  //! surface must stay in view.
  double own_surface_in_view() const {
    size_t seen = 0, total = 0;
    for (uint32_t v = 0; v < setup.arrays.vertex_count(); v += 7, ++total) seen += sees(v, nearest_cell(v));
    return double(seen) / double(total);
  }
};

TEST(SkeletonRegions, SeparateTubesDoNotSeeEachOther) {
  Prepared p("parallel-tubes");
  const SkeletonGraph& g = p.setup.initial.skeleton.graph;
  ASSERT_EQ(g.component_count, 2);
  auto component_of_bone = [&](uint32_t b) { return g.component[size_t(g.edges[b][0])]; };
  size_t tested = 0;
  for (uint32_t v = 0; v < p.setup.arrays.vertex_count(); v += 5)
    for (uint32_t c = 0; c < p.setup.cells.cell_count(); c += 3) {
      if (component_of_bone(p.regions().cell_bones[c]) == component_of_bone(p.regions().vertex_bones[v])) continue;
      EXPECT_FALSE(p.sees(v, c)) << "vertex " << v << " sees cell " << c << " of the other tube";
      ++tested;
    }
  EXPECT_GT(tested, 1000u);
  EXPECT_GT(p.own_surface_in_view(), 0.99);
}

TEST(SkeletonRegions, ATightKnotsOtherPassIsOutOfView) {
  Prepared p("tight-knot");
  // Cells within two radii of a vertex that it may not see: the other pass,
  // whose surface comes within one radius of this one's.
  double r = p.setup.median_radius;
  size_t hidden_nearby = 0;
  for (uint32_t v = 0; v < p.setup.arrays.vertex_count(); v += 3)
    for (uint32_t c = 0; c < p.setup.cells.cell_count(); c += 2)
      hidden_nearby += (p.centroid(c) - p.vertex(v)).norm() < 2.0 * r && !p.sees(v, c);
  EXPECT_GT(hidden_nearby, 100u);
  EXPECT_GT(p.own_surface_in_view(), 0.99);
}

TEST(SkeletonRegions, AThinBranchLooksOnlyAsFarAsItsRadius) {
  Prepared p("thin-branch");
  const SkeletonRegions& r = p.regions();
  auto [lowest, highest] = std::minmax_element(r.vertex_scale.begin(), r.vertex_scale.end());
  EXPECT_NEAR(*lowest, 0.2, 0.05) << "the branch is a fifth of the trunk";
  EXPECT_NEAR(*highest, 1.0, 0.1);
  EXPECT_GT(p.own_surface_in_view(), 0.97);
}

}  // namespace
}  // namespace mcquad
