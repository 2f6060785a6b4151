#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "mesh/folds.h"

namespace mcquad {
namespace {

Eigen::Vector3d at_angle(double degrees, double length) {
  double a = degrees * M_PI / 180.0;
  return length * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
}

TEST(Folds, NormalsFoldOnlyBeyondOneHundredTwentyDegreesWhateverTheirLength) {
  const Eigen::Vector3d up(1, 0, 0);
  for (double length : {1e-6, 1.0, 1e6}) {
    EXPECT_FALSE(normals_fold(up, at_angle(0, length)));
    EXPECT_FALSE(normals_fold(up, at_angle(90, length)));
    EXPECT_FALSE(normals_fold(up, at_angle(119, length)));
    EXPECT_TRUE(normals_fold(up, at_angle(121, length)));
    EXPECT_TRUE(normals_fold(up, at_angle(180, length)));
  }
}

TEST(Folds, ACubeHasNoFoldAndAFaceTurnedOverItsNeighbourHasOne) {
  EXPECT_EQ(folded_edges(test::unit_cube()), 0u);
  // Two quads on a hinge along x = 0, the second folded back on the first.
  QuadMesh hinge;
  auto p = [&](double x, double y, double z) { return hinge.add_vertex(QuadMesh::Point(x, y, z)); };
  auto a = p(-1, 0, 0), b = p(0, 0, 0), c = p(0, 1, 0), d = p(-1, 1, 0), e = p(-0.9, 0, 0.1), f = p(-0.9, 1, 0.1);
  hinge.add_face(a, b, c, d);
  hinge.add_face(b, e, f, c);
  EXPECT_EQ(folded_edges(hinge), 1u);
}

}  // namespace
}  // namespace mcquad
