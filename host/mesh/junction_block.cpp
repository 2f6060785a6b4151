#include "mesh/junction_block.h"

#include <algorithm>
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

std::vector<Port> add_junction_block(QuadSoup& soup, const Eigen::Vector3d& center, const JunctionLayout& layout,
                                     const JunctionBones& bones,
                                     const std::function<double(const Eigen::Vector3d&, double)>& reach, bool closed) {
  auto place = [&](Eigen::Vector3d direction) {
    if (direction.norm() < 1e-9) direction = Eigen::Vector3d::UnitZ();
    direction.normalize();
    double wanted = tube_union_reach(bones, direction);
    return soup.add_vertex(center + std::min(wanted, reach(direction, wanted)) * direction, true);
  };
  std::vector<int> corner_vertex, edge_vertex;
  for (const auto& u : layout.corner_directions) corner_vertex.push_back(place(u));
  for (const auto& e : layout.edges)
    edge_vertex.push_back(place(layout.corner_directions[size_t(e[0])] + layout.corner_directions[size_t(e[1])]));

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
