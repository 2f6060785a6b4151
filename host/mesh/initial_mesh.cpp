#include "mesh/initial_mesh.h"

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/point_index.h"
#include "core/point_text.h"
#include "core/shared_math.h"
#include "io/openmesh_messages.h"
#include "mesh/cloud_probe.h"
#include "mesh/crossing_guard.h"
#include "mesh/crossing_relaxation.h"
#include "mesh/quad_relaxation.h"
#include "mesh/quad_shape.h"
#include "mesh/cube_block.h"
#include "mesh/face_intersections.h"
#include "mesh/folds.h"
#include "mesh/frames.h"
#include "mesh/inset_port.h"
#include "mesh/junction_block.h"
#include "mesh/junction_inflation.h"
#include "mesh/mesh_arrays.h"
#include "mesh/open_ends.h"
#include "mesh/polyline.h"
#include "mesh/quad_soup.h"
#include "mesh/refinement.h"
#include "skeleton/acute_junctions.h"
#include "skeleton/bone_assignment.h"

namespace mcquad {
namespace {

constexpr int kRing = 8;  // vertices around a tube in the rough mesh
// A tube leaves its port straight for a while before turning toward its bone,
// so neighbouring ports' tubes do not crowd the block edge between them.
constexpr double kPortWeight = 1.4;
// The most a ring takes of its port's tilt (MeshAssembler::sweep_chain), in
// the length b of the blend it loses it over. A ring vertex x b along the
// blend, its port vertex t ahead, stands x b - (1 - tilt_kept(x)) t past
// that vertex: behind it somewhere on the blend once t > 0.89 b (a short
// chain between two forks of the 40-degree fan had a port vertex 0.83
// ahead over a blend of 0.71).
constexpr double kMostTilt = 0.4;
// The least a tilted ring's vertex advances along the path from the one
// before it, in the rings' spacing along the path.
constexpr double kLeastTiltedAdvance = 0.5;
// A junction whose bones all lie within this angle of their own cube face's
// normal gets the cube block (docs/CONSTRUCTION.md, section 3; DESIGN.md has
// the measurements). The forks the acute-junction step creates (three bones,
// two of them close) are better served by the general block even 10 to 25
// degrees off a cube, and so are junctions of five and six fat bones: random
// tree 34's, 24.7 degrees off a cube, took the cube while this was 25 for
// five bones on, and its initial mesh turned 0.65 % of its area against the
// true surface, its fit 0.41 % (0.13 and 0.07 % with the general block;
// docs/HARD_CASES.md, 2026-12-07, on junctions of five and six bones and
// the cube).
constexpr double kCubeFitDegrees = 10.0;
// A limb narrower than this, in its first bone's radius, where the blend
// from a grown block ends, keeps its junction's block at the start fraction
// (MeshAssembler::block_fraction). Measured: the generated thin branch
// narrows to 0.21, the octopus's tapering arms to 0.39.
constexpr double kLeastLimbNarrowing = 0.3;

std::string node_name(const SkeletonGraph& graph, int node) {
  return "skeleton node at " + point_text(graph.positions[node]);
}

//! Which block a junction of at most six bones gets: the cube only where
//! its bones fit one (kCubeFitDegrees), or the cube wherever it can be built.
enum class BlockPreference { kFitted, kCube };

class MeshAssembler {
 public:
  MeshAssembler(const TubeSkeleton& skeleton, const PointCloud& cloud, const PointIndex<float>& cloud_index,
                const InitialMeshOptions& options, const std::string& source)
      : graph_(skeleton.graph),
        skeleton_(skeleton),
        cloud_(cloud),
        options_(options),
        source_(source),
        cloud_index_(cloud_index),
        probe_(cloud, cloud_index) {}

  //! Returns whether the preference mattered: some junction of at most six
  //! bones got the general block.
  bool build_blocks(bool closed, BlockPreference preference) {
    bool preference_mattered = false;
    for (size_t node = 0; node < graph_.node_count(); ++node) {
      if (graph_.kind(int(node)) != NodeKind::kJunction) continue;
      Block block = add_block(int(node), closed, preference, preference_mattered);
      if (options_.limb_ports && !closed) inset_thin_limbs(int(node), block);
      const auto& neighbours = graph_.neighbours[node];
      for (size_t k = 0; k < block.ports.size(); ++k) {
        ports_[{int(node), neighbours[k]}] = block.ports[k];
        blend_length_[{int(node), neighbours[k]}] =
            blend_length(int(node), int(k), block.bones.directions, block.ports[k], block.size, block.fraction);
      }
    }
    return preference_mattered;
  }

  //! A junction's block as added to the soup.
  struct Block {
    double fraction = 0;  //!< of the way to the cloud
    double size = 0;
    JunctionBones bones;
    std::vector<Port> ports;  //!< one per bone, in the node's neighbour order
  };

  Block add_block(int node, bool closed, BlockPreference preference, bool& preference_mattered) {
    const Eigen::Vector3d& center = graph_.positions[size_t(node)];
    Block block;
    block.fraction = block_fraction(node);
    block.bones = junction_bones(node, block.fraction);
    block.size = block_size(block.bones);
    const JunctionBones& bones = block.bones;
    // Where the bones fit a cube's faces (every bone near its own face's
    // normal), the cube block: measured on the existing shapes, it is the
    // better one there. Otherwise the general block (junction_layout.h):
    // any valence, any directions.
    BlockOrientation cube;
    bool cube_fits = bones.directions.size() <= 6;
    if (cube_fits) {
      cube = orient_cube_block(bones.directions);
      cube_fits = preference == BlockPreference::kCube || cube.worst_cosine >= std::cos(kCubeFitDegrees * M_PI / 180.0);
      preference_mattered = preference_mattered || !cube_fits;
    }
    // Where tubes overlap, the cloud can be thinner around the node than
    // any bone's radius (below a moved crotch): each block vertex stays
    // at the block's fraction of the way to the cloud in its direction.
    auto reach = [&](const Eigen::Vector3d& direction, double wanted) {
      return block.fraction * probe_.distance_along(center, direction, wanted / block.fraction);
    };
    if (cube_fits) {
      block.ports = add_cube_block(
          soup_, center, block.size, cube, [&](const Eigen::Vector3d& d) { return reach(d, block.size); }, closed);
      return block;
    }
    JunctionLayout layout;
    try {
      layout = layout_junction(bones.directions, bones.tube_radii);
    } catch (const UnsupportedError& e) {
      throw UnsupportedError(source_ + ": " + node_name(graph_, node) + ": " + e.what());
    }
    block.ports = add_junction_block(soup_, center, layout, bones, reach, closed, options_.block_edges);
    return block;
  }

  //! The bones of `block` whose port is more than kInsetPortRatio times as
  //! wide as their limb's root (limb_root_radius, at the block's fraction),
  //! that leave their port within kInsetLeastCosine of its normal, and whose
  //! inset stands out of the port no further than kInsetLongestLift port
  //! radii (inset_lift): a limb that runs on inside its trunk that far is
  //! not a branch out of the trunk's wall (a thin branch at 20 or 30 degrees,
  //! its fork moved out along the trunk: lifted 1.8 to 2.5 port radii, the
  //! fit's mean 0.5 -> 9.7 % r; docs/HARD_CASES.md, "Thin limbs start at
  //! their trunk's wall").
  struct LimbInset {
    size_t bone = 0;    //!< in the node's neighbour order
    double radius = 0;  //!< the limb's root radius, at the block's fraction
    double lift = 0;    //!< out of the port's plane (inset_lift)
  };
  std::vector<LimbInset> limbs_to_inset(int node, const Block& block) const {
    std::vector<LimbInset> inset;
    const auto& neighbours = graph_.neighbours[size_t(node)];
    for (size_t k = 0; k < block.ports.size(); ++k) {
      const Port& port = block.ports[k];
      if (block.bones.directions[k].dot(port.outward) < kInsetLeastCosine) continue;
      const double root = limb_root_radius(node, neighbours[k]);
      if (port.radius <= kInsetPortRatio * block.fraction * root) continue;
      const double lift = inset_lift(node, neighbours[k], port);
      if (lift <= kInsetLongestLift * port.radius) inset.push_back({k, block.fraction * root, lift});
    }
    return inset;
  }

  //! How far out of `port`'s plane the inset of the limb from `node`
  //! through `next` stands: to kInsetLift of the way along the limb to where
  //! it leaves the junction's other tubes (limb_exit), the trunk's wall;
  //! never into the block.
  double inset_lift(int node, int next, const Port& port) const {
    const std::vector<Eigen::Vector3d> line = chain_line(node, next);
    const Eigen::Vector3d root = point_at(line, kInsetLift * limb_exit(node, next, line)).first;
    return std::max(0.0, (root - port.center).dot(port.outward));
  }

  //! Gives each limb of `block` far thinner than its port (limbs_to_inset) a
  //! port of its own size at its root (limb_root_radius), inset in that port
  //! (inset_port) and lifted out of the port's plane to the trunk's wall
  //! (inset_lift), where the limb's tube then starts. In the port's plane,
  //! at the start fraction, the inset lay inside the trunk and the thin
  //! branch's fit got worse; growing the whole block to the wall instead
  //! moved its other ports too and cost the armadillo's torso its coverage
  //! (docs/HARD_CASES.md, "Thin limbs start at their trunk's wall").
  void inset_thin_limbs(int node, Block& block) {
    for (const LimbInset& limb : limbs_to_inset(node, block)) {
      Port& port = block.ports[limb.bone];
      port = inset_port(soup_, port, graph_.positions[size_t(node)], block.bones.directions[limb.bone], limb.radius,
                        limb.lift);
      ++inset_ports_;
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
  int inset_ports() const { return inset_ports_; }
  const CloudProbe& probe() const { return probe_; }

 private:
  //! Radius of the initial tube on the bone from `node` toward `next`, at
  //! `fraction` of the cloud's (the start fraction unless given).
  double tube_radius(int node, int next, double fraction = 0) const {
    if (fraction <= 0) fraction = options_.start_fraction;
    for (size_t b = 0; b < graph_.edges.size(); ++b) {
      const auto& e = graph_.edges[b];
      if ((e[0] == node && e[1] == next) || (e[1] == node && e[0] == next)) return fraction * skeleton_.bone_radius[b];
    }
    return fraction * skeleton_.node_radius[node];
  }

  //! The directions of a junction's bones and their tubes' radii at
  //! `fraction`.
  JunctionBones junction_bones(int node, double fraction) const {
    JunctionBones bones;
    for (int next : graph_.neighbours[size_t(node)]) {
      bones.directions.push_back((graph_.positions[size_t(next)] - graph_.positions[size_t(node)]).normalized());
      bones.tube_radii.push_back(tube_radius(node, next, fraction));
    }
    return bones;
  }

  //! The radius of the limb from junction `node` through `next` at its
  //! root: its first bone's, unless limb_radius finds that bone fat (it took
  //! the points of the tube the junction sits in). Then it is measured in
  //! the cloud just past where the chain leaves the tubes of the junction's
  //! other bones (root_of_limb): the median distance to the cloud of kRing
  //! rays across it. Not the chain's median radius: a limb that tapers (the
  //! armadillo's tail, bones 0.097, 0.054, 0.029, 0.024, 0.019) is thicker
  //! at its root than along most of its length; nor its second bone's: the
  //! generated thin branch's second bone still measures its trunk (0.77 of
  //! it, the branch 0.2).
  double limb_root_radius(int node, int next) const {
    const std::vector<double> radii = chain_radii(node, next);
    if (limb_radius(radii) == radii.front()) return radii.front();
    const std::vector<Eigen::Vector3d> line = chain_line(node, next);
    const double root = root_of_limb(node, next, line);
    if (root <= 0) return radii.front();
    const auto [at, tangent] = point_at(line, root);
    const Eigen::Vector3d u = any_perpendicular(tangent), v = tangent.cross(u);
    std::array<double, kRing> distance;
    for (int i = 0; i < kRing; ++i) {
      const double angle = 2.0 * M_PI * i / kRing;
      distance[size_t(i)] = probe_.distance_along(at, std::cos(angle) * u + std::sin(angle) * v, 2.0 * radii.front());
    }
    std::nth_element(distance.begin(), distance.begin() + kRing / 2, distance.end());
    return std::min(distance[kRing / 2], radii.front());
  }

  //! The chain from junction `node` through `next`, as points.
  std::vector<Eigen::Vector3d> chain_line(int node, int next) const {
    std::vector<Eigen::Vector3d> line;
    for (int c : graph_.chain_from(node, next)) line.push_back(graph_.positions[size_t(c)]);
    return line;
  }

  //! Arc length along `line` (the chain from `node` through `next`) a tenth
  //! past where it leaves the tubes of the node's other bones (limb_exit); 0
  //! if it never does.
  double root_of_limb(int node, int next, const std::vector<Eigen::Vector3d>& line) const {
    return std::min(1.1 * limb_exit(node, next, line), polyline_length(line));
  }

  //! Arc length along `line` (the chain from `node` through `next`) where it
  //! leaves the tubes of the node's other bones (inside_another_tube); 0 if
  //! it never does. Not a fixed distance: a branch at 45 degrees to a trunk
  //! leaves it 1.41 trunk radii out, at 90 degrees 1.
  double limb_exit(int node, int next, const std::vector<Eigen::Vector3d>& line) const {
    const double length = polyline_length(line), step = 0.05 * tube_radius(node, next, 1.0);
    for (double s = step; s <= length; s += step)
      if (!inside_another_tube(node, next, point_at(line, s).first)) return s;
    return 0;
  }

  //! Whether `p` lies inside the tube of a bone of junction `node` other than
  //! the one toward `next`: each a half-line from the node with its first
  //! bone's radius in the cloud.
  bool inside_another_tube(int node, int next, const Eigen::Vector3d& p) const {
    const Eigen::Vector3d& center = graph_.positions[size_t(node)];
    for (int other : graph_.neighbours[size_t(node)]) {
      if (other == next) continue;
      const Eigen::Vector3d axis = (graph_.positions[size_t(other)] - center).normalized();
      const Eigen::Vector3d offset = p - center;
      const double along = std::max(0.0, offset.dot(axis));
      if ((offset - along * axis).norm() < tube_radius(node, other, 1.0)) return true;
    }
    return false;
  }

  //! The bone radii along the chain from junction `node` through `next`.
  std::vector<double> chain_radii(int node, int next) const {
    const std::vector<int> chain = graph_.chain_from(node, next);
    std::vector<double> radii;
    for (size_t k = 0; k + 1 < chain.size(); ++k) radii.push_back(tube_radius(chain[k], chain[k + 1], 1.0));
    return radii;
  }

  static double block_size(const JunctionBones& bones) {
    double largest_ring = *std::max_element(bones.tube_radii.begin(), bones.tube_radii.end());
    return largest_ring / 0.76;  // the cube's ring lies at 0.76 of its size from its axis
  }

  //! The fraction of the cloud's radius a junction's block is built at: the
  //! block fraction (robust mode: 0.9, above the tubes' 0.7, so the tubes
  //! leave the block nearer to the creases between them; docs/DESIGN.md,
  //! "Junction blocks nearer the cloud"), except where a limb is not a tube
  //! as wide as its bone says all along its blend from the grown block: it
  //! ends within it (a stub on a body: the armadillo's back, where the grown
  //! block swallowed the stub and left the body uncovered), or narrows to
  //! less than kLeastLimbNarrowing of its first bone's radius (a thin branch
  //! off a trunk, whose first bone takes the trunk's radius: its port stood
  //! out of the trunk's wall). The start fraction there.
  double block_fraction(int node) const {
    const double grown = std::max(options_.block_fraction, options_.start_fraction);
    if (grown == options_.start_fraction) return grown;
    const JunctionBones bones = junction_bones(node, grown);
    const double size = block_size(bones);
    const auto& neighbours = graph_.neighbours[size_t(node)];
    for (size_t k = 0; k < neighbours.size(); ++k) {
      Port straight;  // the port facing its bone, as a block built at `grown` has it
      straight.outward = bones.directions[k];
      straight.radius = bones.tube_radii[k];
      const double blend = blend_length(node, int(k), bones.directions, straight, size, grown);
      const double there = bone_radius_along(node, neighbours[k], blend);
      if (there < kLeastLimbNarrowing * bones.tube_radii[k] / grown) return options_.start_fraction;
    }
    return grown;
  }

  //! The cloud's radius on the branch from junction `node` through `next`,
  //! `distance` along it (on its last bone where it reaches a junction
  //! sooner); 0 where it ends sooner.
  double bone_radius_along(int node, int next, double distance) const {
    const std::vector<int> chain = graph_.chain_from(node, next);
    for (size_t k = 1; k < chain.size(); ++k) {
      distance -= (graph_.positions[size_t(chain[k])] - graph_.positions[size_t(chain[k - 1])]).norm();
      const bool last = k + 1 == chain.size();
      if (distance <= 0 || (last && graph_.kind(chain[k]) != NodeKind::kEnd))
        return tube_radius(chain[k - 1], chain[k], 1.0);
    }
    return 0;  // the limb ends sooner
  }

  //! How far along bone k of a junction its tube rejoins the skeleton: past
  //! the block, and past where its tube clears every neighbour's (two tubes
  //! of radii a, b on bones at angle t separate at (a + b) / (2 sin(t/2))).
  //! The turn from the port's direction to the bone's needs room too: its
  //! radius of curvature stays well above the ring's radius.
  double blend_length(int node, int k, const std::vector<Eigen::Vector3d>& directions, const Port& port,
                      double block_size, double fraction) const {
    const auto& neighbours = graph_.neighbours[node];
    double own = tube_radius(node, neighbours[k], fraction);
    double turn = std::acos(std::clamp(port.outward.dot(directions[k]), -1.0, 1.0));
    double length = std::max(1.5 * block_size, block_size + 3.0 * port.radius * turn);
    for (size_t j = 0; j < directions.size(); ++j) {
      if (int(j) == k) continue;
      double angle = std::acos(std::clamp(directions[k].dot(directions[j]), -1.0, 1.0));
      double clearance =
          (own + tube_radius(node, neighbours[j], fraction)) / (2.0 * std::max(std::sin(angle / 2), 1e-3));
      length = std::max(length, 1.2 * clearance);
    }
    return length;
  }

  bool end_is_open(int node, const Eigen::Vector3d& outward) {
    if (options_.ends == EndMode::kOpen) return true;
    if (options_.ends == EndMode::kCapped) return false;
    return cloud_is_open_at(cloud_index_, cloud_, graph_.positions[node], outward, skeleton_.node_radius[node]);
  }

  void sweep_chain(const Branch& branch) {
    std::vector<Eigen::Vector3d> skeleton;
    skeleton.reserve(branch.nodes.size());
    for (int node : branch.nodes) skeleton.push_back(graph_.positions[node]);
    int first = branch.nodes.front(), last = branch.nodes.back();
    const Port* start_port = nullptr;
    const Port* end_port = nullptr;
    if (!branch.closed && graph_.kind(first) == NodeKind::kJunction) start_port = &ports_.at({first, branch.nodes[1]});
    if (!branch.closed && graph_.kind(last) == NodeKind::kJunction)
      end_port = &ports_.at({last, branch.nodes[branch.nodes.size() - 2]});

    // Centre line: skeleton polyline, with Hermite blends from the ports.
    double length = polyline_length(skeleton);
    // Both blends must fit on the chain, leaving a little of it straight.
    double blend_in = start_port ? blend_length_.at({first, branch.nodes[1]}) : 0.0;
    double blend_out = end_port ? blend_length_.at({last, branch.nodes[branch.nodes.size() - 2]}) : 0.0;
    double fit = std::min(1.0, 0.9 * length / std::max(blend_in + blend_out, 1e-12));
    double s0 = blend_in * fit;
    double s1 = length - blend_out * fit;
    std::vector<Eigen::Vector3d> centre;
    if (branch.closed) {
      centre = skeleton;
    } else {
      std::vector<Eigen::Vector3d> middle = sub_polyline(skeleton, s0, s1);
      if (start_port) {
        auto [q, tq] = point_at(skeleton, s0);
        centre = hermite_curve(start_port->center, start_port->outward, q, tq, 16, kPortWeight, 2.0 - kPortWeight);
        centre.pop_back();
      }
      centre.insert(centre.end(), middle.begin(), middle.end());
      if (end_port) {
        auto [q, tq] = point_at(skeleton, s1);
        auto blend = hermite_curve(q, tq, end_port->center, -end_port->outward, 16, 2.0 - kPortWeight, kPortWeight);
        centre.insert(centre.end(), blend.begin() + 1, blend.end());
      }
    }
    double radius_first = start_port ? start_port->radius : tube_radius(first, branch.nodes[1]);
    double radius_last = end_port ? end_port->radius : tube_radius(last, branch.nodes[branch.nodes.size() - 2]);
    double radius_mid = 0;
    for (size_t k = 0; k + 1 < branch.nodes.size(); ++k)
      radius_mid += tube_radius(branch.nodes[k], branch.nodes[k + 1]);
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
    const double total = path.length();
    const double in = start_port ? s0 : total / 3, out = end_port ? length - s1 : total / 3;
    auto radius_at = [&](int k) {
      if (branch.closed) return radius_mid;
      double s = path.arc_length[k];
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
    // A port's ring lies on the block, tilted against the path where the
    // bone leaves its face obliquely; the first rings keep that tilt and
    // lose it over the blend, so that none falls behind the port's ring on
    // its forward side (random tree 11: a port vertex 0.46 ahead, the first
    // ring 0.42 ahead, their edge 0.065 long against 0.48).
    std::array<int, kRing> previous = start_ring;
    const std::array<double, kRing> start_tilt = port_tilt(start_port ? &start_ring : nullptr, path, 0);
    const std::array<double, kRing> end_tilt = port_tilt(end_port ? &end_ring : nullptr, path, k_end);
    auto tilt_at = [&](int k) {
      Tilt tilt{{}, &previous, end_port && k + 1 == k_end ? &end_ring : nullptr};
      double s = path.arc_length[k];
      double from_start = tilt_kept(s / std::max(in, 1e-12));
      double from_end = tilt_kept((total - s) / std::max(out, 1e-12));
      for (int i = 0; i < kRing; ++i)
        tilt.ahead[size_t(i)] = from_start * std::min(start_tilt[size_t(i)], kMostTilt * in) +
                                from_end * std::max(end_tilt[size_t(i)], -kMostTilt * out);
      return tilt;
    };
    for (int k = 1; k <= k_end; ++k) {
      std::array<int, kRing> ring;
      if (k == k_end && (end_port || branch.closed))
        ring = end_ring;
      else
        ring = make_ring(path, u, k, radius_at(k), twist * path.arc_length[k] / path.length(), tilt_at(k));
      connect_rings(previous, ring);
      previous = ring;
    }
    if (!branch.closed && !start_port) finish_end(first, start_ring, path.points[0], -path.tangents[0], radius_at(0));
    if (!branch.closed && !end_port)
      finish_end(last, previous, path.points.back(), path.tangents.back(), radius_at(k_end));
  }

  static std::vector<Eigen::Vector3d> closed_copy(std::vector<Eigen::Vector3d> line) {
    line.push_back(line.front());
    return line;
  }

  //! The share of its port's tilt a ring keeps a fraction x of the way along
  //! its blend: all of it at the port, none from the blend's end on, and
  //! eased at both (a smoothstep), so that the rings' spacing has no kink
  //! where the tilt runs out.
  static double tilt_kept(double x) {
    if (x >= 1) return 0;
    return (1 - x) * (1 - x) * (1 + 2 * x);
  }

  //! How far each vertex of a port's `ring` lies ahead of path point k along
  //! the path (zeros without a ring): the plane that fits the ring best, by
  //! the mean and first harmonic of the leads round it. A block's ring is not
  //! flat (a cube face's corners lag its edges' midpoints); that crown stays
  //! with the port, and only the plane's tilt carries on: carried whole over
  //! the blend, or over its first two rings only, the theta's fitted
  //! surfaces met 6.2 and 6.6 degrees apart at a seam there (SurfacesOnShapes).
  std::array<double, kRing> port_tilt(const std::array<int, kRing>* ring, const SweepPath& path, int k) const {
    std::array<double, kRing> tilt{};
    if (!ring) return tilt;
    double mean = 0, along_cos = 0, along_sin = 0;
    for (int i = 0; i < kRing; ++i) {
      const double lead = (soup_.vertices[(*ring)[size_t(i)]] - path.points[k]).dot(path.tangents[k]);
      const double angle = 2.0 * M_PI * i / kRing;
      mean += lead / kRing;
      along_cos += 2.0 * lead * std::cos(angle) / kRing;
      along_sin += 2.0 * lead * std::sin(angle) / kRing;
    }
    for (int i = 0; i < kRing; ++i) {
      const double angle = 2.0 * M_PI * i / kRing;
      tilt[size_t(i)] = mean + along_cos * std::cos(angle) + along_sin * std::sin(angle);
    }
    return tilt;
  }

  //! A ring's share of its ports' tilts (sweep_chain): how far ahead along
  //! the path each vertex goes, and the ring before it.
  struct Tilt {
    std::array<double, kRing> ahead{};
    const std::array<int, kRing>* previous = nullptr;
    const std::array<int, kRing>* next = nullptr;  //!< the end port's ring, after the chain's last ring
  };

  //! Where a tilted ring's vertex i at `p` stands along `tangent`, at least
  //! `least` ahead of its neighbour on the ring before. Where the path bends,
  //! a ring's inner side advances less than its centre: there the tilt is
  //! let go no faster than the ring advances. The ports' rings are not flat
  //! (port_tilt), and the chain's last ring also stays that far short of the
  //! end port's; between the two, where they leave less room, it stands
  //! halfway.
  Eigen::Vector3d spaced(const Eigen::Vector3d& p, const Eigen::Vector3d& tangent, double least, const Tilt& tilt,
                         int i) const {
    const double at = p.dot(tangent);
    const Eigen::Vector3d& before = soup_.vertices[(*tilt.previous)[size_t(i)]];
    const double lowest = tilt.ahead[size_t(i)] != 0 ? before.dot(tangent) + least : -INFINITY;
    const double highest = tilt.next ? soup_.vertices[(*tilt.next)[size_t(i)]].dot(tangent) - least : INFINITY;
    if (lowest > highest) return halfway(p, tangent, before, soup_.vertices[(*tilt.next)[size_t(i)]]);
    return p + (std::clamp(at, lowest, highest) - at) * tangent;
  }

  //! Where a ring vertex at `p` stands between its neighbours `before` and
  //! `after` on two ports' rings that leave it too little room along
  //! `tangent`: halfway along it, or halfway between them, whichever leaves
  //! its shorter edge to them the longer (random tree 14 at 20,000 points
  //! needed the second, random tree 10 at 30,000 the first).
  static Eigen::Vector3d halfway(const Eigen::Vector3d& p, const Eigen::Vector3d& tangent,
                                 const Eigen::Vector3d& before, const Eigen::Vector3d& after) {
    const Eigen::Vector3d between = 0.5 * (before + after);
    const Eigen::Vector3d along = p + (between - p).dot(tangent) * tangent;
    auto shorter_edge = [&](const Eigen::Vector3d& q) { return std::min((q - before).norm(), (q - after).norm()); };
    return shorter_edge(along) >= shorter_edge(between) ? along : between;
  }

  std::array<int, kRing> make_ring(const SweepPath& path, const std::vector<Eigen::Vector3d>& u, int k, double radius,
                                   double twist, const std::optional<Tilt>& tilt = std::nullopt) {
    std::array<int, kRing> ring;
    Eigen::Vector3d v = path.tangents[k].cross(u[k]);
    std::array<Eigen::Vector3d, kRing> radial;
    for (int i = 0; i < kRing; ++i) {
      double angle = 2.0 * M_PI * i / kRing + twist;
      radial[size_t(i)] = std::cos(angle) * u[k] + std::sin(angle) * v;
    }
    // Where the cloud is thinner than the bone's radius (tubes merging near
    // a junction, a thin branch leaving a thick trunk), the ring follows it
    // at the same start fraction, centred in the cloud's cross-section: the
    // centre line's blend from a port can pass off a thin branch's axis, and
    // a ring cut short on one side only would collapse against its wall.
    // A tilted ring's vertex looks for the cloud from where it will stand along the path.
    Eigen::Vector3d centre = path.points[k];
    const Eigen::Vector3d& tangent = path.tangents[k];
    std::array<double, kRing> distance, ahead{};
    if (tilt) ahead = tilt->ahead;
    double enough = radius / options_.start_fraction;
    for (int pass = 0; pass < 3; ++pass) {
      for (int i = 0; i < kRing; ++i)
        distance[size_t(i)] =
            probe_.distance_along(centre + ahead[size_t(i)] * tangent, radial[size_t(i)], 2.0 * enough);
      if (*std::min_element(distance.begin(), distance.end()) >= enough || pass == 2) break;
      // Opposite directions see the wall at R + d.r and R - d.r from a centre
      // off by d; over the four pairs 45 degrees apart, their differences
      // sum to twice d. Pairs with a side open (or a ray that slipped through
      // a gap in the samples) say nothing.
      Eigen::Vector3d offset = Eigen::Vector3d::Zero();
      for (int i = 0; i < kRing / 2; ++i) {
        double a = distance[size_t(i)], b = distance[size_t(i + kRing / 2)];
        if (a < 2.0 * enough && b < 2.0 * enough) offset += 0.25 * (a - b) * radial[size_t(i)];
      }
      if (offset.norm() > 0.5 * radius) offset *= 0.5 * radius / offset.norm();
      centre += offset;
    }
    for (int i = 0; i < kRing; ++i) {
      Eigen::Vector3d p = centre + ahead[size_t(i)] * tangent +
                          std::min(radius, options_.start_fraction * distance[size_t(i)]) * radial[size_t(i)];
      if (tilt) p = spaced(p, tangent, kLeastTiltedAdvance * (path.arc_length[k] - path.arc_length[k - 1]), *tilt, i);
      ring[i] = soup_.add_vertex(p);
    }
    return ring;
  }

  //! The cyclic offset of `target` (CCW about `tangent`) that best continues
  //! the swept frame, and the twist left over, in (-pi, pi].
  double closing_twist(const std::array<int, kRing>& target, const Eigen::Vector3d& center,
                       const Eigen::Vector3d& tangent, const Eigen::Vector3d& u, int& best_offset) {
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
    // Like the rings, the cap stops at the start fraction of the way to the
    // cloud: where two merged tubes end side by side (acute_junctions.h) the
    // cloud's end is notched in the middle, nearer than the radius.
    radius = std::min(
        radius, options_.start_fraction * probe_.distance_along(center, outward, radius / options_.start_fraction));
    std::array<int, kRing> cap_ring;
    for (int i = 0; i < kRing; ++i) {
      Eigen::Vector3d radial = soup_.vertices[ring[i]] - center;
      cap_ring[i] = soup_.add_vertex(center + 0.45 * radius * outward + 0.8 * radial, true);
    }
    if (ccw_about_outward)
      connect_rings(ring, cap_ring);
    else
      connect_rings(cap_ring, ring);
    int middle = soup_.add_vertex(center + 0.8 * radius * outward, true);
    for (int k = 0; k < 4; ++k) {
      int a = cap_ring[2 * k], b = cap_ring[2 * k + 1], c = cap_ring[(2 * k + 2) % kRing];
      if (ccw_about_outward)
        soup_.quads.push_back({middle, a, b, c});
      else
        soup_.quads.push_back({middle, c, b, a});
    }
    for (int id : ring) soup_.irregular_allowed[id] = true;
  }

  const SkeletonGraph& graph_;
  const TubeSkeleton& skeleton_;
  const PointCloud& cloud_;
  const InitialMeshOptions& options_;
  std::string source_;
  const PointIndex<float>& cloud_index_;
  CloudProbe probe_;
  QuadSoup soup_;
  std::map<std::pair<int, int>, Port> ports_;
  std::map<std::pair<int, int>, double> blend_length_;
  int open_ends_ = 0;
  int inset_ports_ = 0;
};

QuadMesh to_openmesh(const QuadSoup& soup, const std::string& source) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> handles;
  handles.reserve(soup.vertices.size());
  for (const auto& p : soup.vertices) handles.push_back(mesh.add_vertex(QuadMesh::Point(p.x(), p.y(), p.z())));
  OpenMeshMessages quiet;  // the error below says it, in one line
  for (size_t f = 0; f < soup.quads.size(); ++f) {
    const auto& q = soup.quads[f];
    auto face =
        mesh.add_face(std::vector<QuadMesh::VertexHandle>{handles[q[0]], handles[q[1]], handles[q[2]], handles[q[3]]});
    if (!face.is_valid()) {
      const Eigen::Vector3d& at = soup.vertices[size_t(q[0])];
      throw OverlapError(source + ": the initial mesh is not a manifold at quad " + std::to_string(f) + " (at " +
                             point_text(at) + "): two tubes or blocks of this skeleton overlap there",
                         {at.x(), at.y(), at.z()});
    }
  }
  return mesh;
}

double mean_edge_length(const QuadMesh& mesh) {
  double sum = 0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return mesh.n_edges() ? sum / mesh.n_edges() : 0.0;
}

int refinement_levels(const QuadMesh& mesh, const InitialMeshOptions& options) {
  int levels = 1;  // 8 -> 16 vertices around a tube (docs/DESIGN.md)
  if (options.target_vertices > 0) {
    levels = 0;
    for (size_t v = mesh.n_vertices(); v < options.target_vertices && levels < 7; v *= 4) ++levels;
  } else if (options.resolution > 0) {
    levels = std::max(0, int(std::ceil(std::log2(mean_edge_length(mesh) / options.resolution) - 1e-9)));
  }
  if (levels > 7)
    throw UnsupportedError("the requested resolution needs " + std::to_string(levels) +
                           " refinement levels (at most 7 are supported)");
  return levels;
}

//! The mesh before refinement, with the assembler that built it (refinement
//! needs it to move vertices back inside the cloud).
struct CoarseMesh {
  std::unique_ptr<MeshAssembler> assembler;
  InitialMesh result;
  bool preference_mattered = false;  //!< some junction of at most six bones got the general block
};

CoarseMesh assemble_coarse_mesh(const TubeSkeleton& skeleton, const PointCloud& cloud,
                                const PointIndex<float>& cloud_index, const InitialMeshOptions& options,
                                const std::string& source, BlockPreference preference);
//! The coarse mesh refined `levels` times, folds relaxed, moved back inside the cloud.
QuadMesh refined(const CoarseMesh& coarse, int levels, double junction_inflation);

//! Whether `point` lies within `radius` plus a bone's radius of any bone
//! not at `node`: an end moved there would run its tube into that one.
bool nears_another_bone(const TubeSkeleton& skeleton, int node, const Eigen::Vector3d& point, double radius) {
  const SkeletonGraph& graph = skeleton.graph;
  for (size_t b = 0; b < graph.edges.size(); ++b) {
    const auto& e = graph.edges[b];
    if (e[0] == node || e[1] == node) continue;
    const double distance =
        segment_distance(point, graph.positions[size_t(e[0])], graph.positions[size_t(e[1])], nullptr);
    if (distance < radius + skeleton.bone_radius[b]) return true;
  }
  return false;
}

//! End nodes short of where the cloud's tube ends (skeletons of other tools
//! stop inside the tips; issue 14) move out along their last bone: a capped
//! end to one radius short of the cloud's tip, where a cap centred there
//! reaches it, an open end to where the tube's wall stops. An end in place
//! stays: a cap's tip is a radius beyond it, an open wall stops there.
void reach_the_cloud_ends(TubeSkeleton& skeleton, const PointCloud& cloud, const PointIndex<float>& index,
                          EndMode ends) {
  SkeletonGraph& graph = skeleton.graph;
  const double spacing = index.median_spacing();
  for (size_t node = 0; node < graph.node_count(); ++node) {
    if (graph.kind(int(node)) != NodeKind::kEnd) continue;
    const Eigen::Vector3d end = graph.positions[node];
    const Eigen::Vector3d outward = (end - graph.positions[size_t(graph.neighbours[node][0])]).normalized();
    const double radius = skeleton.node_radius[node];
    const double extent = cloud_extent_beyond(index, cloud, end, outward, radius, std::max(spacing, 0.1 * radius));
    if (extent <= 0.25 * radius) continue;  // an open end where the wall stops
    // Open or capped as decided at the node itself; a move that would make
    // the end look otherwise (another limb's points beyond a short one) is
    // not made, so moving never changes what an end is.
    auto open_at = [&](const Eigen::Vector3d& p) {
      return ends == EndMode::kOpen || (ends == EndMode::kAuto && cloud_is_open_at(index, cloud, p, outward, radius));
    };
    const bool open = open_at(end);
    const Eigen::Vector3d moved = end + (open ? extent : std::max(extent - radius, 0.0)) * outward;
    if (open_at(moved) != open || nears_another_bone(skeleton, int(node), moved, radius)) continue;
    graph.positions[node] = moved;
  }
}

}  // namespace

InitialMesh build_initial_mesh(const SkeletonGraph& graph, const BoneAssignment& bones, const PointCloud& cloud,
                               const InitialMeshOptions& options, const std::string& source,
                               const PointIndex<float>* cloud_index) {
  std::unique_ptr<PointIndex<float>> own_index;
  if (!cloud_index) cloud_index = (own_index = std::make_unique<PointIndex<float>>(cloud.points)).get();
  // Checked before acute junctions move: a node's valence is what the user gave.
  for (size_t node = 0; node < graph.node_count(); ++node) {
    try {
      check_junction_valence(graph.neighbours[node].size());
    } catch (const UnsupportedError& e) {
      throw UnsupportedError(source + ": " + node_name(graph, int(node)) + ": " + e.what());
    }
  }
  TubeSkeleton skeleton = spread_acute_junctions(graph, bones, options.min_junction_angle, source);
  reach_the_cloud_ends(skeleton, cloud, *cloud_index, options.ends);
  // The cube where the bones fit it, the general block elsewhere; where that
  // leaves faces crossing and the cube could serve more junctions, the mesh
  // with the cube wherever it can is built too, and the one with fewer
  // crossing pairs is kept (docs/DESIGN.md: neither block is cleaner on
  // every shape and scan). Both are compared refined once (the default
  // resolution), whatever resolution is asked for, so every resolution
  // makes the same choice.
  InitialMeshOptions used = options;
  CoarseMesh coarse = assemble_coarse_mesh(skeleton, cloud, *cloud_index, used, source, BlockPreference::kFitted);
  // The unrefined mesh (8 vertices round a tube) keeps its blocks at the
  // start fraction and their edge vertices midway: its faces are too coarse
  // to stand nearer the cloud or to turn toward a crotch (the 60-degree Y's
  // crotch crossed itself, 7 pairs, and a node of the octopus fell outside
  // its mesh; with the edges on the bisector, 23 pairs); refined, they are
  // smoothed apart. No port is inset either: at the start fraction the thin
  // branch's inset lay inside the trunk, and a node of the branch outside
  // its mesh.
  if (options.stage == ConstructionStage::kRefined &&
      (used.block_fraction > used.start_fraction || used.block_edges != BlockEdges::kMidway || used.limb_ports) &&
      refinement_levels(coarse.result.mesh, options) == 0) {
    used.block_fraction = used.start_fraction;
    used.block_edges = BlockEdges::kMidway;
    used.limb_ports = false;
    coarse = assemble_coarse_mesh(skeleton, cloud, *cloud_index, used, source, BlockPreference::kFitted);
  }
  if (coarse.preference_mattered && options.stage == ConstructionStage::kRefined) {
    size_t crossings = intersecting_face_pairs(refined(coarse, 1, options.junction_inflation)).size();
    if (crossings > 0) {
      CoarseMesh cubes = assemble_coarse_mesh(skeleton, cloud, *cloud_index, used, source, BlockPreference::kCube);
      if (intersecting_face_pairs(refined(cubes, 1, options.junction_inflation)).size() < crossings)
        coarse = std::move(cubes);
    }
  }
  InitialMesh& result = coarse.result;
  if (options.stage == ConstructionStage::kRefined) {
    int levels = refinement_levels(result.mesh, options);
    result.refinement_levels = options.coarse_first ? std::min(levels, 1) : levels;
    result.finer_levels = levels - result.refinement_levels;
    result.mesh = refined(coarse, result.refinement_levels, options.junction_inflation);
    result.irregular_allowed.resize(result.mesh.n_vertices(), false);
  }
  return std::move(result);
}

namespace {

//! Folds and crossing faces relaxed away, in turns, since smoothing one can
//! bring back the other (until crossings are left that smoothing cannot part).
void untangle(QuadMesh& mesh) {
  for (int turn = 0; turn < 4; ++turn) {
    relax_folds(mesh, 3);
    if (relax_crossings(mesh) > 0 || folded_edges(mesh) == 0) return;
  }
}

//! A refined mesh and how many of its quads stay under
//! CrossingGuard::kLeastScaledJacobian.
struct RefinedMesh {
  QuadMesh mesh;
  size_t poor_left = 0;
};

//! refined() with the quads the refinement left poor straightened before
//! the junctions are inflated (`straighten_first`) or not.
RefinedMesh refined_with(const CoarseMesh& coarse, int levels, double junction_inflation, bool straighten_first) {
  QuadMesh mesh = coarse.result.mesh;
  // Junctions are inflated at the default resolution (the unrefined mesh,
  // 8 vertices round a tube, is too coarse to follow the rays: its rings
  // left their bones): finer levels smooth the moved mesh as they refine
  // it; inflated after them, 0.8 % of a T's area turned in its creases.
  const int inflate_after = std::min(levels, 1);
  // Level by level: a crossing is smoothed away at the coarsest level it
  // appears, where a few rounds move whole faces, not slivers of them.
  // The last level's crossings are looked for once, after the move inside.
  for (int level = 0; level < levels; ++level) {
    refine_catmull_clark(mesh, 1);
    if (level + 1 < levels)
      untangle(mesh);
    else
      relax_folds(mesh);
    if (level + 1 == inflate_after && junction_inflation > 0) {
      if (straighten_first) relax_poor_quads(mesh, CrossingGuard::kLeastScaledJacobian);
      inflate_junctions(mesh, coarse.result.skeleton, coarse.assembler->probe(), junction_inflation);
    }
  }
  coarse.assembler->probe().keep_inside(mesh);
  // Moving back inside can fold a face in a tight crease. The unrefined
  // mesh (8 vertices round a tube) is only relaxed where it folds:
  // smoothing a crossing there would shrink whole tubes onto their bones.
  size_t poor_left = 0;
  if (levels == 0) {
    relax_folds(mesh);
  } else {
    untangle(mesh);
    poor_left = relax_poor_quads(mesh, CrossingGuard::kLeastScaledJacobian);
  }
  return {std::move(mesh), poor_left};
}

QuadMesh refined(const CoarseMesh& coarse, int levels, double junction_inflation) {
  RefinedMesh first = refined_with(coarse, levels, junction_inflation, false);
  if (first.poor_left == 0 || junction_inflation <= 0 || levels == 0) return std::move(first.mesh);
  // The inflation's guard holds a poor quad to where it starts, and the
  // crease vertices round it with it, so what the refinement left poor can
  // stay poor to the end (random tree 10: 0.10). Built again with those
  // quads straightened before the inflation, the mesh whose worst quad is
  // better is kept. Not always the second: straightened first, random tree
  // 8's worst quad fell from 0.30 to 0.01 (docs/CONSTRUCTION.md).
  RefinedMesh straightened = refined_with(coarse, levels, junction_inflation, true);
  if (measure_quad_shape(straightened.mesh).min_scaled_jacobian > measure_quad_shape(first.mesh).min_scaled_jacobian)
    return std::move(straightened.mesh);
  return std::move(first.mesh);
}

CoarseMesh assemble_coarse_mesh(const TubeSkeleton& skeleton, const PointCloud& cloud,
                                const PointIndex<float>& cloud_index, const InitialMeshOptions& options,
                                const std::string& source, BlockPreference preference) {
  CoarseMesh coarse;
  coarse.assembler = std::make_unique<MeshAssembler>(skeleton, cloud, cloud_index, options, source);
  MeshAssembler& assembler = *coarse.assembler;
  coarse.preference_mattered = assembler.build_blocks(options.stage == ConstructionStage::kBlocks, preference);
  if (options.stage == ConstructionStage::kBlocks) {
    if (assembler.soup().quads.empty())
      throw InputError(source + ": the skeleton has no junction, so there are no blocks");
  } else {
    assembler.build_chains();
  }
  coarse.result.mesh = to_openmesh(assembler.soup(), source);
  coarse.result.skeleton = skeleton;
  coarse.result.open_ends = assembler.open_ends();
  coarse.result.inset_ports = assembler.inset_ports();
  coarse.result.irregular_allowed = assembler.soup().irregular_allowed;
  return coarse;
}

}  // namespace

void refine_fitted_mesh(QuadMesh& mesh, int levels) {
  for (int level = 0; level < levels; ++level) {
    refine_catmull_clark(mesh, 1);
    untangle(mesh);
  }
  // Refined, a fitted quad at the guard's least scaled Jacobian (0.3) can
  // split into quads well under it where the fit bends (random trees 14
  // and 17 one level finer: 0.30 -> 0.18 and 0.29 -> 0.15), and the guard
  // keeps each quad at least where it starts: relaxed here, as the rough
  // mesh's are (docs/HARD_CASES.md, "Doublets").
  if (levels > 0) relax_poor_quads(mesh, CrossingGuard::kLeastScaledJacobian);
}

}  // namespace mcquad
