#include "mesh/inset_port.h"

#include <algorithm>
#include <cmath>

namespace mcquad {
namespace {

//! Where the bone's axis crosses the port's plane, kept within half the
//! port's radius of its centre: a bone that leaves nearly along its face
//! (or is far off its centre) would put the inset ring past the port's.
Eigen::Vector3d inset_center(const Port& port, const Eigen::Vector3d& node, const Eigen::Vector3d& direction) {
  constexpr double kLeastCosine = 0.2;  // about 78 degrees off the port's normal
  const double along = direction.dot(port.outward);
  if (along < kLeastCosine) return port.center;
  const Eigen::Vector3d crossing = node + direction * ((port.center - node).dot(port.outward) / along);
  const Eigen::Vector3d offset = crossing - port.center;
  const double farthest = 0.5 * port.radius;
  return offset.norm() <= farthest ? crossing : Eigen::Vector3d(port.center + farthest * offset.normalized());
}

//! The axis of an inset ring of `radius` lifted `lift` out of a port with
//! `normal`: its bone's `direction` where the ring, tilted across the bone,
//! stays clear of the port's plane (its lowest point at least half the lift
//! above it), the port's normal otherwise. Across the bone, the limb's tube
//! starts as it goes on; in the face's plane, the frustum from the face's
//! lower edge to a ring 34 degrees off the branch's cross-section crossed
//! the obtuse corner below a thin branch at 50 degrees outside the cloud
//! (mean / p95 2.54 / 8.71 -> 1.16 / 2.38 % r; docs/HARD_CASES.md, "Thin
//! limbs start at their trunk's wall").
Eigen::Vector3d ring_axis(const Eigen::Vector3d& normal, const Eigen::Vector3d& direction, double radius, double lift) {
  const double cosine = std::clamp(direction.dot(normal), -1.0, 1.0);
  const double drop = radius * std::sqrt(1.0 - cosine * cosine);  // the tilted ring's lowest point below its centre
  return cosine > 0 && drop <= 0.5 * lift ? direction : normal;
}

}  // namespace

Port inset_port(QuadSoup& soup, const Port& port, const Eigen::Vector3d& node, const Eigen::Vector3d& direction,
                double radius, double lift) {
  const Eigen::Vector3d& normal = port.outward;
  Port lifted = port;
  lifted.center += lift * normal;
  Port inner;
  inner.center = inset_center(lifted, node, direction);
  inner.outward = ring_axis(normal, direction, radius, lift);
  inner.radius = radius;
  // Each inner vertex toward its outer one, across the ring's axis, so the
  // ring keeps the port's order and the band's quads their shape.
  for (size_t k = 0; k < 8; ++k) {
    Eigen::Vector3d toward = soup.vertices[size_t(port.ring[k])] - port.center;
    toward -= toward.dot(normal) * normal;
    toward -= toward.dot(inner.outward) * inner.outward;
    inner.ring[k] = soup.add_vertex(inner.center + radius * toward.normalized(), true);
  }
  // Counter-clockwise seen from outside: the port's ring runs
  // counter-clockwise about `normal`, the band from it inward.
  for (size_t k = 0; k < 8; ++k) {
    const size_t next = (k + 1) % 8;
    soup.quads.push_back({port.ring[k], port.ring[next], inner.ring[next], inner.ring[k]});
  }
  return inner;
}

}  // namespace mcquad
