#include "mesh/initial_mesh.h"

#include <cmath>
#include <map>
#include <sstream>

#include "core/errors.h"
#include "core/point_index.h"
#include "mesh/frames.h"
#include "mesh/junction_block.h"
#include "mesh/open_ends.h"
#include "mesh/quad_soup.h"
#include "mesh/refinement.h"

namespace mcquad {
namespace {

constexpr int kRing = 8;  // vertices around a tube in the rough mesh

std::string node_name(const SkeletonGraph& graph, int node) {
  std::ostringstream s;
  s << "skeleton node at (" << graph.positions[node].transpose() << ")";
  return s.str();
}

//! A point at arc length s along a polyline, with the unit tangent there.
std::pair<Eigen::Vector3d, Eigen::Vector3d> point_at(const std::vector<Eigen::Vector3d>& line, double s) {
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    double span = (line[i + 1] - line[i]).norm();
    if (s <= span || i + 2 == line.size()) {
      double t = span > 0 ? std::clamp(s / span, 0.0, 1.0) : 0.0;
      return {line[i] + t * (line[i + 1] - line[i]), (line[i + 1] - line[i]).normalized()};
    }
    s -= span;
  }
  return {line.back(), Eigen::Vector3d::UnitZ()};
}

double polyline_length(const std::vector<Eigen::Vector3d>& line) {
  double length = 0;
  for (size_t i = 0; i + 1 < line.size(); ++i) length += (line[i + 1] - line[i]).norm();
  return length;
}

//! The part of a polyline between arc lengths s0 and s1.
std::vector<Eigen::Vector3d> sub_polyline(const std::vector<Eigen::Vector3d>& line, double s0, double s1) {
  std::vector<Eigen::Vector3d> out{point_at(line, s0).first};
  double s = 0;
  for (size_t i = 0; i + 1 < line.size(); ++i) {
    s += (line[i + 1] - line[i]).norm();
    if (s > s0 && s < s1) out.push_back(line[i + 1]);
  }
  out.push_back(point_at(line, s1).first);
  return out;
}

class MeshAssembler {
 public:
  MeshAssembler(const SkeletonGraph& graph, const BoneAssignment& bones, const PointCloud& cloud,
                const InitialMeshOptions& options, const std::string& source)
      : graph_(graph), bones_(bones), cloud_(cloud), options_(options), source_(source), cloud_index_(cloud.points) {}

  void build_blocks() {
    for (size_t node = 0; node < graph_.node_count(); ++node) {
      if (graph_.kind(int(node)) != NodeKind::kJunction) continue;
      const Eigen::Vector3d& center = graph_.positions[node];
      std::vector<Eigen::Vector3d> directions;
      double largest_ring = 0;
      for (int next : graph_.neighbours[node]) {
        directions.push_back((graph_.positions[next] - center).normalized());
        largest_ring = std::max(largest_ring, tube_radius(int(node), next));
      }
      BlockOrientation orientation;
      try {
        orientation = orient_block(directions);
      } catch (const UnsupportedError& e) {
        throw UnsupportedError(source_ + ": " + node_name(graph_, int(node)) + ": " + e.what());
      }
      // A face group's ring lies at about 0.76 of the block's size from its
      // axis; size the block so the ring matches the widest bone's tube.
      double size = largest_ring / 0.76;
      block_size_[int(node)] = size;
      std::vector<Port> ports = add_junction_block(soup_, center, size, orientation);
      for (size_t k = 0; k < ports.size(); ++k) ports_[{int(node), graph_.neighbours[node][k]}] = ports[k];
    }
  }

  void build_chains() {
    for (Branch branch : graph_.branches()) {
      if (!branch.closed && graph_.kind(branch.nodes.front()) != NodeKind::kJunction &&
          graph_.kind(branch.nodes.back()) == NodeKind::kJunction)
        std::reverse(branch.nodes.begin(), branch.nodes.end());
      sweep_chain(branch);
    }
  }

  QuadSoup& soup() { return soup_; }
  int open_ends() const { return open_ends_; }

 private:
  //! Radius of the initial tube on the bone from `node` toward `next`.
  double tube_radius(int node, int next) const {
    for (size_t b = 0; b < graph_.edges.size(); ++b) {
      const auto& e = graph_.edges[b];
      if ((e[0] == node && e[1] == next) || (e[1] == node && e[0] == next)) return options_.start_fraction * bones_.bone_radius[b];
    }
    return options_.start_fraction * bones_.node_radius[node];
  }

  bool end_is_open(int node, const Eigen::Vector3d& outward) {
    if (options_.ends == EndMode::kOpen) return true;
    if (options_.ends == EndMode::kCapped) return false;
    return cloud_is_open_at(cloud_index_, cloud_, graph_.positions[node], outward, bones_.node_radius[node]);
  }

  void sweep_chain(const Branch& branch) {
    std::vector<Eigen::Vector3d> skeleton;
    for (int node : branch.nodes) skeleton.push_back(graph_.positions[node]);
    int first = branch.nodes.front(), last = branch.nodes.back();
    const Port* start_port = nullptr;
    const Port* end_port = nullptr;
    if (!branch.closed && graph_.kind(first) == NodeKind::kJunction) start_port = &ports_.at({first, branch.nodes[1]});
    if (!branch.closed && graph_.kind(last) == NodeKind::kJunction)
      end_port = &ports_.at({last, branch.nodes[branch.nodes.size() - 2]});

    // Centre line: skeleton polyline, with Hermite blends from the ports.
    double length = polyline_length(skeleton);
    double s0 = start_port ? std::min(1.5 * block_size_.at(first), 0.35 * length) : 0.0;
    double s1 = end_port ? length - std::min(1.5 * block_size_.at(last), 0.35 * length) : length;
    std::vector<Eigen::Vector3d> centre;
    if (branch.closed) {
      centre = skeleton;
    } else {
      std::vector<Eigen::Vector3d> middle = sub_polyline(skeleton, s0, s1);
      if (start_port) {
        auto [q, tq] = point_at(skeleton, s0);
        centre = hermite_curve(start_port->center, start_port->outward, q, tq, 16);
        centre.pop_back();
      }
      centre.insert(centre.end(), middle.begin(), middle.end());
      if (end_port) {
        auto [q, tq] = point_at(skeleton, s1);
        auto blend = hermite_curve(q, tq, end_port->center, -end_port->outward, 16);
        centre.insert(centre.end(), blend.begin() + 1, blend.end());
      }
    }
    double radius_first = start_port ? start_port->radius : tube_radius(first, branch.nodes[1]);
    double radius_last = end_port ? end_port->radius : tube_radius(last, branch.nodes[branch.nodes.size() - 2]);
    double radius_mid = 0;
    for (size_t k = 0; k + 1 < branch.nodes.size(); ++k) radius_mid += tube_radius(branch.nodes[k], branch.nodes[k + 1]);
    if (branch.closed) radius_mid += tube_radius(last, first);
    radius_mid /= double(branch.closed ? branch.nodes.size() : branch.nodes.size() - 1);

    double centre_length = polyline_length(branch.closed ? closed_copy(centre) : centre);
    double spacing = 2.0 * M_PI * radius_mid / kRing;
    int segments = std::max(branch.closed ? 3 : 2, int(std::lround(centre_length / spacing)));
    SweepPath path = resample_polyline(centre, segments, branch.closed);

    Eigen::Vector3d initial = start_port ? Eigen::Vector3d(soup_.vertices[start_port->ring[0]] - start_port->center)
                                         : any_perpendicular(path.tangents[0]);
    std::vector<Eigen::Vector3d> u = rotation_minimizing_frames(path, initial);

    // Radius along the path: the tube's, blending from and to the rings of
    // the ports over the Hermite blends (a third of the chain at free ends).
    auto radius_at = [&](int k) {
      if (branch.closed) return radius_mid;
      double s = path.arc_length[k], total = path.length();
      double in = start_port ? s0 : total / 3, out = end_port ? length - s1 : total / 3;
      if (total - s < s && total - s < out) return radius_last + (radius_mid - radius_last) * (total - s) / out;
      if (s < in) return radius_first + (radius_mid - radius_first) * s / in;
      return radius_mid;
    };

    // Closing ring (a port or the loop's own first ring) and the twist to spread.
    std::array<int, kRing> start_ring{};
    bool have_start = start_port != nullptr;
    if (have_start) start_ring = start_port->ring;
    std::array<int, kRing> end_ring{};
    double twist = 0;
    int k_end = segments;
    if (!have_start) start_ring = make_ring(path, u, 0, radius_at(0), 0.0);
    if (end_port || branch.closed) {
      std::array<int, kRing> target = start_ring;
      Eigen::Vector3d target_center = path.points[0];
      if (end_port) {
        for (int i = 0; i < kRing; ++i) target[i] = end_port->ring[(kRing - i) % kRing];  // CCW about the path
        target_center = end_port->center;
      }
      int offset = 0;
      twist = closing_twist(target, target_center, path.tangents[k_end], u[k_end], offset);
      for (int i = 0; i < kRing; ++i) end_ring[i] = target[(i + offset) % kRing];
    }
    std::array<int, kRing> previous = start_ring;
    for (int k = 1; k <= k_end; ++k) {
      std::array<int, kRing> ring;
      if (k == k_end && (end_port || branch.closed)) ring = end_ring;
      else ring = make_ring(path, u, k, radius_at(k), twist * path.arc_length[k] / path.length());
      connect_rings(previous, ring);
      previous = ring;
    }
    if (!branch.closed && !start_port) finish_end(first, start_ring, path.points[0], -path.tangents[0], radius_at(0));
    if (!branch.closed && !end_port) finish_end(last, previous, path.points.back(), path.tangents.back(), radius_at(k_end));
  }

  static std::vector<Eigen::Vector3d> closed_copy(std::vector<Eigen::Vector3d> line) {
    line.push_back(line.front());
    return line;
  }

  std::array<int, kRing> make_ring(const SweepPath& path, const std::vector<Eigen::Vector3d>& u, int k, double radius,
                                   double twist) {
    std::array<int, kRing> ring;
    Eigen::Vector3d v = path.tangents[k].cross(u[k]);
    for (int i = 0; i < kRing; ++i) {
      double angle = 2.0 * M_PI * i / kRing + twist;
      ring[i] = soup_.add_vertex(path.points[k] + radius * (std::cos(angle) * u[k] + std::sin(angle) * v));
    }
    return ring;
  }

  //! The cyclic offset of `target` (CCW about `tangent`) that best continues
  //! the swept frame, and the twist left over, in (-pi, pi].
  double closing_twist(const std::array<int, kRing>& target, const Eigen::Vector3d& center, const Eigen::Vector3d& tangent,
                       const Eigen::Vector3d& u, int& best_offset) {
    double best = 1e30, best_twist = 0;
    for (int offset = 0; offset < kRing; ++offset) {
      double sin_sum = 0, cos_sum = 0;
      for (int i = 0; i < kRing; ++i) {
        double beta = signed_angle(u, soup_.vertices[target[(i + offset) % kRing]] - center, tangent);
        double delta = beta - 2.0 * M_PI * i / kRing;
        sin_sum += std::sin(delta);
        cos_sum += std::cos(delta);
      }
      double twist = std::atan2(sin_sum, cos_sum);
      if (std::abs(twist) < best) {
        best = std::abs(twist);
        best_twist = twist;
        best_offset = offset;
      }
    }
    return best_twist;
  }

  //! Quads between two rings, both CCW about the direction from a to b.
  void connect_rings(const std::array<int, kRing>& a, const std::array<int, kRing>& b) {
    for (int i = 0; i < kRing; ++i) {
      int j = (i + 1) % kRing;
      soup_.quads.push_back({a[i], a[j], b[j], b[i]});
    }
  }

  //! Caps an end with a face group (an extra ring, then a fan of four quads
  //! round a centre vertex), or leaves it open. `ring` is CCW about the chain
  //! direction, `outward` points out of the tube.
  void finish_end(int node, const std::array<int, kRing>& ring, const Eigen::Vector3d& center,
                  const Eigen::Vector3d& outward, double radius) {
    if (end_is_open(node, outward)) {
      ++open_ends_;
      return;
    }
    Eigen::Vector3d axis_ccw = (soup_.vertices[ring[1]] - center).cross(soup_.vertices[ring[2]] - center).normalized();
    bool ccw_about_outward = axis_ccw.dot(outward) > 0;
    std::array<int, kRing> cap_ring;
    for (int i = 0; i < kRing; ++i) {
      Eigen::Vector3d radial = soup_.vertices[ring[i]] - center;
      cap_ring[i] = soup_.add_vertex(center + 0.45 * radius * outward + 0.8 * radial, true);
    }
    if (ccw_about_outward) connect_rings(ring, cap_ring);
    else connect_rings(cap_ring, ring);
    int middle = soup_.add_vertex(center + 0.8 * radius * outward, true);
    for (int k = 0; k < 4; ++k) {
      int a = cap_ring[2 * k], b = cap_ring[2 * k + 1], c = cap_ring[(2 * k + 2) % kRing];
      if (ccw_about_outward) soup_.quads.push_back({middle, a, b, c});
      else soup_.quads.push_back({middle, c, b, a});
    }
    for (int id : ring) soup_.irregular_allowed[id] = true;
  }

  const SkeletonGraph& graph_;
  const BoneAssignment& bones_;
  const PointCloud& cloud_;
  const InitialMeshOptions& options_;
  std::string source_;
  PointIndex<float> cloud_index_;
  QuadSoup soup_;
  std::map<std::pair<int, int>, Port> ports_;
  std::map<int, double> block_size_;
  int open_ends_ = 0;
};

QuadMesh to_openmesh(const QuadSoup& soup, const std::string& source) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> handles;
  handles.reserve(soup.vertices.size());
  for (const auto& p : soup.vertices) handles.push_back(mesh.add_vertex(QuadMesh::Point(p.x(), p.y(), p.z())));
  for (size_t f = 0; f < soup.quads.size(); ++f) {
    const auto& q = soup.quads[f];
    auto face = mesh.add_face(std::vector<QuadMesh::VertexHandle>{handles[q[0]], handles[q[1]], handles[q[2]], handles[q[3]]});
    if (!face.is_valid())
      throw UnsupportedError(source + ": the initial mesh construction produced a non-manifold configuration at quad " +
                             std::to_string(f) + " (please report this skeleton)");
  }
  return mesh;
}

double mean_edge_length(const QuadMesh& mesh) {
  double sum = 0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return mesh.n_edges() ? sum / mesh.n_edges() : 0.0;
}

int refinement_levels(const QuadMesh& mesh, const InitialMeshOptions& options) {
  int levels = 2;  // 8 -> 32 vertices around a tube
  if (options.target_vertices > 0) {
    levels = 0;
    for (double v = double(mesh.n_vertices()); v < double(options.target_vertices) && levels < 7; v *= 4) ++levels;
  } else if (options.resolution > 0) {
    levels = std::max(0, int(std::ceil(std::log2(mean_edge_length(mesh) / options.resolution) - 1e-9)));
  }
  if (levels > 7) throw UnsupportedError("the requested resolution needs " + std::to_string(levels) +
                                         " refinement levels (at most 7 are supported)");
  return levels;
}

}  // namespace

InitialMesh build_initial_mesh(const SkeletonGraph& graph, const BoneAssignment& bones, const PointCloud& cloud,
                               const InitialMeshOptions& options, const std::string& source) {
  MeshAssembler assembler(graph, bones, cloud, options, source);
  assembler.build_blocks();
  InitialMesh result;
  if (options.stage == "blocks") {
    if (assembler.soup().quads.empty()) throw InputError(source + ": the skeleton has no junction, so there are no blocks");
  } else {
    assembler.build_chains();
  }
  result.mesh = to_openmesh(assembler.soup(), source);
  result.open_ends = assembler.open_ends();
  result.irregular_allowed = assembler.soup().irregular_allowed;
  if (options.stage == "refined") {
    result.refinement_levels = refinement_levels(result.mesh, options);
    refine_catmull_clark(result.mesh, result.refinement_levels);
    result.irregular_allowed.resize(result.mesh.n_vertices(), false);
  }
  return result;
}

}  // namespace mcquad
