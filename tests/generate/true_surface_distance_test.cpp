#include <gtest/gtest.h>

#include "generate/true_surface_distance.h"
#include "helpers.h"

namespace mcquad {
namespace {

//! The true surface's inward area: a box round a capsule faces out (0), the
//! box turned inside out faces in (1), one face turned over is a sixth.
TEST(TrueSurfaceDistance, InwardAreaIsTheShareOfFacesAgainstTheTrueNormal) {
  TubeSurface surface;
  surface.add(Capsule{Eigen::Vector3d(0.5, 0.5, 0.2), Eigen::Vector3d(0.5, 0.5, 0.8), 0.3});
  EXPECT_DOUBLE_EQ(inward_area_fraction(test::unit_cube(), surface), 0.0);
  EXPECT_DOUBLE_EQ(inward_area_fraction(test::unit_cube(true), surface), 1.0);
  // The box's faces apart (OpenMesh joins no faces of opposite turns), the
  // top (+z) one with its corners in the opposite order.
  const QuadMesh cube = test::unit_cube();
  QuadMesh one_turned;
  for (auto f : cube.faces()) {
    std::vector<QuadMesh::VertexHandle> corners;
    Eigen::Vector3d centre = face_centroid(cube, f.idx());
    for (auto v : cube.fv_range(f)) corners.push_back(one_turned.add_vertex(cube.point(v)));
    if (centre.z() > 0.9) std::reverse(corners.begin(), corners.end());
    one_turned.add_face(corners);
  }
  EXPECT_NEAR(inward_area_fraction(one_turned, surface), 1.0 / 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(measure_true_surface_distance(test::unit_cube(true), surface).inward_area_fraction, 1.0);
}

//! Every corner of the unit box lies sqrt(0.54) from the capsule's segment:
//! outside a thin capsule (positive), inside a fat one (negative).
TEST(TrueSurfaceDistance, SignedMeanIsNegativeInsideAndPositiveOutside) {
  for (double radius : {0.3, 1.0}) {
    TubeSurface surface;
    surface.add(Capsule{Eigen::Vector3d(0.5, 0.5, 0.2), Eigen::Vector3d(0.5, 0.5, 0.8), radius});
    TrueSurfaceDistance d = measure_true_surface_distance(test::unit_cube(), surface);
    double expected = (std::sqrt(0.54) - radius) / radius;
    EXPECT_NEAR(d.signed_relative_mean, expected, 1e-9) << radius;
    EXPECT_NEAR(d.relative.mean, std::abs(expected), 1e-9) << radius;
  }
}

//! An open end's wall goes on past its rim for a radius, where a fit ends:
//! beyond it lies the round end of that stretch, not more tube. A tube
//! passing 2.5 radii past the rim keeps its own wall (random tree 14's open
//! end had reached into such a wall and measured it as inside the shape).
TEST(TrueSurfaceDistance, AnOpenEndGoesOnForOneRadiusPastItsRim) {
  TubeSurface surface;
  surface.add(Capsule{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 2), 0.5, false, true});
  EXPECT_NEAR(surface.signed_distance(Eigen::Vector3d(0.5, 0, 2.4)), 0.0, 1e-12);  // the wall, extended
  EXPECT_NEAR(surface.signed_distance(Eigen::Vector3d(0, 0, 3.25)), 0.25, 1e-12);  // past the stretch
  // A tube across the axis 2.5 radii past the rim: its wall facing the end is the surface.
  surface.add(Capsule{Eigen::Vector3d(-2, 0, 3.75), Eigen::Vector3d(2, 0, 3.75), 0.5});
  EXPECT_NEAR(surface.signed_distance(Eigen::Vector3d(0.3, 0, 3.25)), 0.0, 1e-12);
}

//! The cloud leaves out what lies inside the open end's extension too (the
//! previous capsule's round end can reach out of a short last one's rim),
//! so the extension must stay short: a tube passing 2.5 radii past the rim
//! is sampled whole (at three radii the wall facing the end had a hole).
TEST(TrueSurfaceDistance, ATubePastAnOpenEndIsSampledWhole) {
  TubeSurface surface;
  surface.add(Capsule{Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 2), 0.5, false, true});
  surface.add(Capsule{Eigen::Vector3d(-2, 0, 3.75), Eigen::Vector3d(2, 0, 3.75), 0.5});
  std::mt19937_64 random(1);
  PointCloud cloud = surface.sample(20000, random, 0.0);
  size_t facing_the_end = 0;
  for (const auto& p : cloud.points)
    if (std::abs(p.x()) < 0.3 && p.z() > 3.2 && p.z() < 3.35) facing_the_end += 1;
  EXPECT_GT(facing_the_end, 20u);
}

}  // namespace
}  // namespace mcquad
