#include "mesh/inset_port.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mcquad {
namespace {

//! A port of radius 1 in the plane z = 0, counter-clockwise about +z.
struct RoundPort {
  QuadSoup soup;
  Port port;
  RoundPort() {
    for (int k = 0; k < 8; ++k) {
      const double angle = M_PI / 4 * k;
      port.ring[size_t(k)] = soup.add_vertex({std::cos(angle), std::sin(angle), 0}, true);
    }
    port.center = Eigen::Vector3d::Zero();
    port.outward = Eigen::Vector3d::UnitZ();
    port.radius = 1;
  }
  Eigen::Vector3d at(int id) const { return soup.vertices[size_t(id)]; }
};

//! Newell's normal of a quad of the soup (twice its area, seen from its side).
Eigen::Vector3d quad_normal(const QuadSoup& soup, const std::array<int, 4>& q) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < 4; ++k) n += soup.vertices[size_t(q[k])].cross(soup.vertices[size_t(q[(k + 1) % 4])]);
  return n;
}

TEST(InsetPort, IsARingOfTheLimbsRadiusWhereItsBoneCrossesThePort) {
  RoundPort r;
  // A bone leaving a node below the port, tilted, crossing z = 0 at (0.3, 0, 0).
  const Eigen::Vector3d node(0.3 - 0.5, 0, -1), direction = Eigen::Vector3d(0.5, 0, 1).normalized();
  Port inner = inset_port(r.soup, r.port, node, direction, 0.25);
  EXPECT_NEAR((inner.center - Eigen::Vector3d(0.3, 0, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(inner.outward, r.port.outward);
  EXPECT_EQ(inner.radius, 0.25);
  for (size_t k = 0; k < 8; ++k) {
    const Eigen::Vector3d p = r.at(inner.ring[k]);
    EXPECT_NEAR((p - inner.center).norm(), 0.25, 1e-12) << k;
    EXPECT_NEAR(p.z(), 0, 1e-12) << "in the port's plane";
    // In the port's order: each inner vertex toward its outer one.
    EXPECT_GT((p - inner.center).normalized().dot(r.at(r.port.ring[k])), 0.99) << k;
  }
  // The band: 8 quads from the port's ring to the inner one, facing out
  // of the block as the port does, every vertex used by two of them.
  ASSERT_EQ(r.soup.quads.size(), 8u);
  std::vector<int> uses(r.soup.vertices.size(), 0);
  for (const auto& q : r.soup.quads) {
    EXPECT_GT(quad_normal(r.soup, q).z(), 0);
    for (int id : q) ++uses[size_t(id)];
  }
  for (int count : uses) EXPECT_EQ(count, 2);
}

TEST(InsetPort, StaysWithinHalfThePortsRadiusOfItsCentre) {
  RoundPort r;
  // A bone nearly in the port's plane: the centre of the port.
  Port flat = inset_port(r.soup, r.port, {0, 0, -1}, Eigen::Vector3d(1, 0, 0.1).normalized(), 0.2);
  EXPECT_NEAR(flat.center.norm(), 0, 1e-12);
  // A bone crossing the plane 0.9 out: held at 0.5.
  Port off = inset_port(r.soup, r.port, {0.9, 0, -1}, Eigen::Vector3d::UnitZ(), 0.2);
  EXPECT_NEAR((off.center - Eigen::Vector3d(0.5, 0, 0)).norm(), 0, 1e-12);
}

TEST(InsetPort, LiftedStandsOutOfThePortAcrossItsBone) {
  RoundPort r;
  // The bone of the first test; lifted by 0.4, it crosses z = 0.4 at (0.5, 0, 0.4).
  const Eigen::Vector3d node(0.3 - 0.5, 0, -1), direction = Eigen::Vector3d(0.5, 0, 1).normalized();
  Port inner = inset_port(r.soup, r.port, node, direction, 0.25, 0.4);
  EXPECT_NEAR((inner.center - Eigen::Vector3d(0.5, 0, 0.4)).norm(), 0, 1e-12);
  EXPECT_NEAR((inner.outward - direction).norm(), 0, 1e-12) << "the ring faces along its bone";
  for (size_t k = 0; k < 8; ++k) {
    const Eigen::Vector3d p = r.at(inner.ring[k]);
    EXPECT_NEAR((p - inner.center).norm(), 0.25, 1e-12) << k;
    EXPECT_NEAR((p - inner.center).dot(direction), 0, 1e-12) << "across the bone";
    EXPECT_GT(p.z(), 0.2) << "clear of the port's plane";
    // In the port's order: each inner vertex toward its outer one.
    EXPECT_GT((p - inner.center).dot(r.at(r.port.ring[k])), 0) << k;
  }
  // The band is a frustum narrowing outward: every quad still faces out of
  // the block, up and away from the axis.
  for (const auto& q : r.soup.quads) {
    const Eigen::Vector3d n = quad_normal(r.soup, q);
    Eigen::Vector3d mid = Eigen::Vector3d::Zero();
    for (int id : q) mid += r.at(id) / 4;
    EXPECT_GT(n.z(), 0);
    EXPECT_GT(n.dot(mid - Eigen::Vector3d(0, 0, mid.z())), 0);
  }
}

TEST(InsetPort, LiftedTooLittleToTurnStaysInALiftedPlane) {
  RoundPort r;
  // Tilted across the bone, the ring would dip 0.11 below its centre: more
  // than half a lift of 0.1, so it stays parallel to the port, at z = 0.1.
  const Eigen::Vector3d node(0.3 - 0.5, 0, -1), direction = Eigen::Vector3d(0.5, 0, 1).normalized();
  Port inner = inset_port(r.soup, r.port, node, direction, 0.25, 0.1);
  EXPECT_EQ(inner.outward, r.port.outward);
  for (size_t k = 0; k < 8; ++k) EXPECT_NEAR(r.at(inner.ring[k]).z(), 0.1, 1e-12) << k;
}

}  // namespace
}  // namespace mcquad
