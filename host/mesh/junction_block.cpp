#include "mesh/junction_block.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mcquad {

double tube_union_reach(const JunctionBones& bones, const Eigen::Vector3d& direction) {
  static const double kLeastSine = std::sin(15.0 * M_PI / 180.0);
  double reach = 0;
  for (size_t i = 0; i < bones.directions.size(); ++i) {
    double cosine = direction.dot(bones.directions[i]);
    double r = bones.tube_radii[i];
    if (cosine > 0) r /= std::max(std::sqrt(std::max(0.0, 1.0 - cosine * cosine)), kLeastSine);
    reach = std::max(reach, r);
  }
  return reach;
}

namespace {

//! The two bones whose faces meet at layout edge `edge`; {-1, -1} where it
//! borders a filler face or the same bone's face twice.
std::array<int, 2> bones_beside(const JunctionLayout& layout, size_t edge) {
  std::array<int, 2> beside{-1, -1};
  int found = 0;
  for (size_t bone = 0; bone < layout.bone_edges.size(); ++bone)
    for (int id : layout.bone_edges[bone])
      if (size_t(id) == edge && found < 2) beside[size_t(found++)] = int(bone);
  if (found != 2 || beside[0] == beside[1]) return {-1, -1};
  return beside;
}

//! How many layout edges the faces of bones `pair` share.
int shared_edges(const JunctionLayout& layout, const std::array<int, 2>& pair) {
  int shared = 0;
  for (int id : layout.bone_edges[size_t(pair[0])])
    for (int other : layout.bone_edges[size_t(pair[1])]) shared += id == other;
  return shared;
}

}  // namespace

Eigen::Vector3d edge_direction(const JunctionLayout& layout, const JunctionBones& bones, size_t edge,
                               BlockEdges placement, const std::function<bool(const Eigen::Vector3d&)>& crotch_at) {
  const auto& e = layout.edges[edge];
  Eigen::Vector3d midway = layout.corner_directions[size_t(e[0])] + layout.corner_directions[size_t(e[1])];
  if (placement == BlockEdges::kMidway) return midway;
  static const double kAcuteCosine = std::cos(kAcuteEdgeDegrees * M_PI / 180.0);
  const std::array<int, 2> beside = bones_beside(layout, edge);
  if (beside[0] < 0) return midway;
  const Eigen::Vector3d& u = bones.directions[size_t(beside[0])];
  const Eigen::Vector3d& v = bones.directions[size_t(beside[1])];
  Eigen::Vector3d bisector = (u + v).normalized();
  if (u.dot(v) <= kAcuteCosine || !crotch_at(bisector)) return midway;
  if (shared_edges(layout, beside) == 1) return bisector;
  // Two bones' faces that share two edges (above and below a fork, or a
  // doubled edge, junction_layout.h) would both land on one point: each
  // goes from the plane halfway between the bones, where the curve their
  // tubes meet on lies, kTowardBisector of the way to the bisector.
  const Eigen::Vector3d across = (u - v).normalized();
  const Eigen::Vector3d onto = midway - midway.dot(across) * across;
  if (onto.norm() <= 1e-6 * midway.norm()) return bisector;
  return (1 - kTowardBisector) * onto.normalized() + kTowardBisector * bisector;
}

std::vector<Port> add_junction_block(QuadSoup& soup, const Eigen::Vector3d& center, const JunctionLayout& layout,
                                     const JunctionBones& bones,
                                     const std::function<double(const Eigen::Vector3d&, double)>& reach, bool closed,
                                     BlockEdges edge_placement) {
  auto place = [&](Eigen::Vector3d direction) {
    if (direction.norm() < 1e-9) direction = Eigen::Vector3d::UnitZ();
    direction.normalize();
    double wanted = tube_union_reach(bones, direction);
    return soup.add_vertex(center + std::min(wanted, reach(direction, wanted)) * direction, true);
  };
  std::vector<int> corner_vertex, edge_vertex;
  for (const auto& u : layout.corner_directions) corner_vertex.push_back(place(u));
  // The cloud has a crotch where the tubes say (their walls meet within
  // kCrotchSlack of where the cloud is). Not so where a fork stands past
  // where its limbs' walls part and its bisector looks down the gap between
  // them (blob-limbs' legs: the vertices went 1.7 out, into the gap).
  auto crotch_at = [&](const Eigen::Vector3d& bisector) {
    const double apex = kCrotchSlack * tube_union_reach(bones, bisector);
    return reach(bisector, apex) < apex;
  };
  for (size_t e = 0; e < layout.edges.size(); ++e)
    edge_vertex.push_back(place(edge_direction(layout, bones, e, edge_placement, crotch_at)));

  // Closed faces in the bones' wide gaps: a fan of quads round a centre each.
  for (size_t f = 0; f < layout.filler_directions.size(); ++f) {
    int middle = place(layout.filler_directions[f]);
    const auto& corners = layout.filler_corners[f];
    const auto& edges = layout.filler_edges[f];
    std::vector<int> boundary;
    for (size_t k = 0; k < corners.size(); ++k) {
      boundary.push_back(edge_vertex[size_t(edges[(k + corners.size() - 1) % corners.size()])]);
      boundary.push_back(corner_vertex[size_t(corners[k])]);
    }
    soup.add_quad_fan(middle, boundary);
  }

  std::vector<Port> ports(bones.directions.size());
  for (size_t b = 0; b < ports.size(); ++b) {
    Port& port = ports[b];
    for (int k = 0; k < 4; ++k) {
      port.ring[size_t(2 * k)] = corner_vertex[size_t(layout.bone_corners[b][size_t(k)])];
      port.ring[size_t(2 * k + 1)] = edge_vertex[size_t(layout.bone_edges[b][size_t(k)])];
    }
    port.center = Eigen::Vector3d::Zero();
    for (int id : port.ring) port.center += soup.vertices[size_t(id)] / 8.0;
    // The ring's mean plane (Newell's normal) is the way the tube leaves;
    // rings of blocks are not flat, a bone's direction can be off that plane.
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d& p = soup.vertices[size_t(port.ring[size_t(k)])];
      const Eigen::Vector3d& q = soup.vertices[size_t(port.ring[size_t((k + 1) % 8)])];
      normal += (p - port.center).cross(q - port.center);
    }
    port.outward = normal.norm() > 1e-12 ? normal.normalized() : bones.directions[b];
    port.radius = 0;
    for (int id : port.ring) port.radius += (soup.vertices[size_t(id)] - port.center).norm() / 8.0;
    if (closed) {  // the ring starts at a corner; the fan at a midpoint
      std::vector<int> boundary(port.ring.begin() + 1, port.ring.end());
      boundary.push_back(port.ring[0]);
      soup.add_quad_fan(soup.add_vertex(port.center + 0.5 * port.radius * port.outward, true), boundary);
    }
  }
  return ports;
}

}  // namespace mcquad
