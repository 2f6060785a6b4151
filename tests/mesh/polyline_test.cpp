#include <gtest/gtest.h>

#include "mesh/polyline.h"

namespace mcquad {
namespace {

using Vec = Eigen::Vector3d;

//! An L: 3 along x, then 4 along y.
const std::vector<Vec> kL{Vec(0, 0, 0), Vec(3, 0, 0), Vec(3, 4, 0)};

TEST(Polyline, LengthIsTheSumOfItsSegments) {
  EXPECT_DOUBLE_EQ(polyline_length(kL), 7.0);
  EXPECT_DOUBLE_EQ(polyline_length({Vec(1, 1, 1)}), 0.0);
}

TEST(Polyline, PointAtArcLengthWithItsTangentClampedToTheEnds) {
  auto [p, t] = point_at(kL, 1.5);
  EXPECT_TRUE(p.isApprox(Vec(1.5, 0, 0)));
  EXPECT_TRUE(t.isApprox(Vec::UnitX()));
  std::tie(p, t) = point_at(kL, 5.0);
  EXPECT_TRUE(p.isApprox(Vec(3, 2, 0)));
  EXPECT_TRUE(t.isApprox(Vec::UnitY()));
  std::tie(p, t) = point_at(kL, 99.0);
  EXPECT_TRUE(p.isApprox(Vec(3, 4, 0))) << "past the end: the end";
  std::tie(p, t) = point_at(kL, -1.0);
  EXPECT_TRUE(p.isApprox(Vec(0, 0, 0))) << "before the start: the start";
}

TEST(Polyline, SubPolylineKeepsTheInnerCornersBetweenItsEnds) {
  std::vector<Vec> part = sub_polyline(kL, 1.0, 5.0);
  ASSERT_EQ(part.size(), 3u);
  EXPECT_TRUE(part[0].isApprox(Vec(1, 0, 0)));
  EXPECT_TRUE(part[1].isApprox(Vec(3, 0, 0)));
  EXPECT_TRUE(part[2].isApprox(Vec(3, 2, 0)));
  EXPECT_NEAR(polyline_length(part), 4.0, 1e-12);
}

}  // namespace
}  // namespace mcquad
