// Taking a limb out of a skeleton (skeleton/limb_removal.h): the fit does it
// to a skeleton it extracted where a limb's tube overlaps another's.
#include <gtest/gtest.h>

#include "skeleton/limb_removal.h"

namespace mcquad {
namespace {

//! A junction at the origin with three limbs along +x (two bones), +y and
//! -y (one bone each).
SkeletonData three_limbs() {
  SkeletonData s;
  s.nodes = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  s.edges = {{0, 1}, {1, 2}, {0, 3}, {0, 4}};
  return s;
}

TEST(LimbRemoval, TakesOutTheWholeLimbNearestTheSite) {
  SkeletonData s = three_limbs();
  // Nearest the +x limb's first bone, the one from the junction.
  auto end = remove_limb_nearest(s, Eigen::Vector3d(0.5, 0.1, 0));
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(*end, Eigen::Vector3d(2, 0, 0));
  ASSERT_EQ(s.nodes.size(), 3u);
  EXPECT_EQ(s.nodes[0], Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(s.nodes[1], Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(s.nodes[2], Eigen::Vector3d(0, -1, 0));
  ASSERT_EQ(s.edges.size(), 2u);
  EXPECT_EQ(s.edges[0], (std::array<int, 2>{0, 1}));
  EXPECT_EQ(s.edges[1], (std::array<int, 2>{0, 2}));
}

TEST(LimbRemoval, MeasuresEveryBoneOfALimb) {
  SkeletonData s = three_limbs();
  // On the +x limb's second bone, away from the junction.
  auto end = remove_limb_nearest(s, Eigen::Vector3d(1.6, 0.05, 0));
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(*end, Eigen::Vector3d(2, 0, 0));
}

TEST(LimbRemoval, LeavesALoneChainAlone) {
  SkeletonData tube;
  tube.nodes = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  tube.edges = {{0, 1}, {1, 2}};
  EXPECT_FALSE(remove_limb_nearest(tube, Eigen::Vector3d(1, 0, 0)).has_value());
  EXPECT_EQ(tube.nodes.size(), 3u);
  EXPECT_EQ(tube.edges.size(), 2u);
}

}  // namespace
}  // namespace mcquad
