#include <gtest/gtest.h>

#include <cmath>

#include "helpers.h"
#include "mesh/cloud_probe.h"

namespace mcquad {
namespace {

//! Points on a sphere of radius `radius` about the origin, about `spacing` apart.
PointCloud sphere_cloud(double radius, double spacing) {
  PointCloud cloud;
  const int rings = int(std::ceil(M_PI * radius / spacing));
  for (int i = 0; i <= rings; ++i) {
    double polar = M_PI * i / rings;
    int around = std::max(1, int(std::round(2 * M_PI * radius * std::sin(polar) / spacing)));
    for (int k = 0; k < around; ++k) {
      double azimuth = 2 * M_PI * k / around;
      cloud.points.emplace_back(float(radius * std::sin(polar) * std::cos(azimuth)),
                                float(radius * std::sin(polar) * std::sin(azimuth)), float(radius * std::cos(polar)));
    }
  }
  return cloud;
}

TEST(CloudProbe, SpacingAndRaysFromTheCentreOfASphere) {
  PointCloud cloud = sphere_cloud(2.0, 0.05);
  PointIndex<float> index(cloud.points);
  CloudProbe probe(cloud, index);
  EXPECT_NEAR(probe.spacing(), 0.05, 0.015);
  for (const Eigen::Vector3d& direction : {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 1).normalized()})
    EXPECT_NEAR(probe.distance_along(Eigen::Vector3d::Zero(), direction, 10.0), 2.0, 0.05) << direction.transpose();
  // Tracing stops once past what the caller needs: at least that far, never past the wall.
  double enough = probe.distance_along(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 0.5);
  EXPECT_GE(enough, 0.5);
  EXPECT_LE(enough, 2.0);
}

TEST(CloudProbe, KeepInsideMovesAMeshOutsideTheCloudBackIn) {
  PointCloud cloud = sphere_cloud(0.4, 0.02);
  for (auto& p : cloud.points) p += Eigen::Vector3f(0.5f, 0.5f, 0.5f);  // about the cube's centre
  PointIndex<float> index(cloud.points);
  CloudProbe probe(cloud, index);
  QuadMesh cube = test::unit_cube();  // corners 0.87 from the centre: outside the sphere
  probe.keep_inside(cube);
  for (auto v : cube.vertices()) {
    double from_centre = (point_of(cube, v) - Eigen::Vector3d(0.5, 0.5, 0.5)).norm();
    EXPECT_LT(from_centre, std::sqrt(0.75)) << "vertex " << v.idx() << " moved inward";
  }
}

}  // namespace
}  // namespace mcquad
