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

//! The two bones whose quads have layout edge or corner `id` (`per_bone`:
//! each bone's 4); {-1, -1} unless exactly two distinct bones do (an edge
//! bordering a filler face, a corner where three bones' quads meet).
std::array<int, 2> two_bones_with(const std::vector<std::array<int, 4>>& per_bone, size_t id) {
  std::array<int, 2> beside{-1, -1};
  int found = 0;
  for (size_t bone = 0; bone < per_bone.size(); ++bone)
    for (int own : per_bone[bone])
      if (size_t(own) == id && found++ < 2) beside[size_t(found - 1)] = int(bone);
  if (found != 2 || beside[0] == beside[1]) return {-1, -1};
  return beside;
}

//! Two bones less than kAcuteEdgeDegrees apart (unit directions).
bool acute(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  static const double kAcuteCosine = std::cos(kAcuteEdgeDegrees * M_PI / 180.0);
  return u.dot(v) > kAcuteCosine;
}

//! How many layout edges the faces of bones `pair` share.
int shared_edges(const JunctionLayout& layout, const std::array<int, 2>& pair) {
  int shared = 0;
  for (int id : layout.bone_edges[size_t(pair[0])])
    for (int other : layout.bone_edges[size_t(pair[1])]) shared += id == other;
  return shared;
}

}  // namespace

Eigen::Vector3d corner_direction(const JunctionLayout& layout, const JunctionBones& bones, size_t corner,
                                 BlockEdges placement, const CrotchFinder& crotch_between) {
  const Eigen::Vector3d& laid_out = layout.corner_directions[corner];
  if (placement == BlockEdges::kMidway) return laid_out;
  // Only a corner between exactly two bones' faces (a doubled edge's
  // two-sided face, junction_layout.h) stands where their crease is.
  for (const auto& filler : layout.filler_corners)
    if (std::find(filler.begin(), filler.end(), int(corner)) != filler.end()) return laid_out;
  const std::array<int, 2> beside = two_bones_with(layout.bone_corners, corner);
  if (beside[0] < 0) return laid_out;
  const Eigen::Vector3d& u = bones.directions[size_t(beside[0])];
  const Eigen::Vector3d& v = bones.directions[size_t(beside[1])];
  if (!acute(u, v)) return laid_out;
  return crotch_between(u, v).value_or(laid_out);
}

Eigen::Vector3d nearest_on_arc(const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                               const std::function<double(const Eigen::Vector3d&)>& distance) {
  const double angle = std::acos(std::clamp(u.dot(v), -1.0, 1.0));
  const Eigen::Vector3d across = (v - u.dot(v) * u).normalized();  // v's part off u
  Eigen::Vector3d best = (u + v).normalized();                     // kept unless clearly farther
  double least = kCrotchLean * distance(best);
  for (int k = kCrotchSamples / 4; k <= 3 * kCrotchSamples / 4; ++k) {
    if (2 * k == kCrotchSamples) continue;  // the bisector
    const double t = angle * double(k) / double(kCrotchSamples);
    const Eigen::Vector3d d = std::cos(t) * u + std::sin(t) * across;
    const double along = distance(d);
    if (along < least) least = along, best = d;
  }
  return best;
}

Eigen::Vector3d edge_direction(const JunctionLayout& layout, const JunctionBones& bones, size_t edge,
                               BlockEdges placement, const CrotchFinder& crotch_between) {
  const auto& e = layout.edges[edge];
  Eigen::Vector3d midway = layout.corner_directions[size_t(e[0])] + layout.corner_directions[size_t(e[1])];
  if (placement == BlockEdges::kMidway) return midway;
  const std::array<int, 2> beside = two_bones_with(layout.bone_edges, edge);
  if (beside[0] < 0) return midway;
  const Eigen::Vector3d& u = bones.directions[size_t(beside[0])];
  const Eigen::Vector3d& v = bones.directions[size_t(beside[1])];
  if (!acute(u, v)) return midway;
  const std::optional<Eigen::Vector3d> crotch = crotch_between(u, v);
  if (!crotch) return midway;
  if (shared_edges(layout, beside) == 1) return *crotch;
  // Two bones' faces that share two edges (above and below a fork, or a
  // doubled edge, junction_layout.h) would both land on one point: each
  // goes from the plane through the crotch square to the bones' plane (the
  // plane halfway between them, where the curve their tubes meet on lies,
  // for tubes alike), kTowardCrotch of the way to the crotch.
  const Eigen::Vector3d across = crotch->cross(u.cross(v)).normalized();
  const Eigen::Vector3d onto = midway - midway.dot(across) * across;
  if (onto.norm() <= 1e-6 * midway.norm()) return *crotch;
  return (1 - kTowardCrotch) * onto.normalized() + kTowardCrotch * *crotch;
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
  // The cloud's crotch between two bones: the direction on the arc between
  // them along which the cloud is nearest (the apex, where the ray leaves
  // the two tubes' union soonest; with unequal radii or a bone that bends
  // past the node it is off the bisector). It counts where the cloud there
  // is nearer than kCrotchSlack times where the tubes' walls would meet. Not
  // so where a fork stands past where its limbs' walls part and the arc
  // looks down the gap between them (blob-limbs' legs: the vertices went 1.7
  // out, into the gap).
  auto crotch_between = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) -> std::optional<Eigen::Vector3d> {
    auto apex = [&](const Eigen::Vector3d& d) { return kCrotchSlack * tube_union_reach(bones, d); };
    const double enough = kCrotchSearch * apex((u + v).normalized());
    Eigen::Vector3d crotch = nearest_on_arc(u, v, [&](const Eigen::Vector3d& d) { return reach(d, enough); });
    if (reach(crotch, apex(crotch)) < apex(crotch)) return crotch;
    return std::nullopt;
  };
  for (size_t c = 0; c < layout.corner_directions.size(); ++c)
    corner_vertex.push_back(place(corner_direction(layout, bones, c, edge_placement, crotch_between)));
  for (size_t e = 0; e < layout.edges.size(); ++e)
    edge_vertex.push_back(place(edge_direction(layout, bones, e, edge_placement, crotch_between)));

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
