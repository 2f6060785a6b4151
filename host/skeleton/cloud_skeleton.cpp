#include "skeleton/cloud_skeleton.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "core/errors.h"
#include "core/point_index.h"
#include "core/quantile.h"
#include "core/union_find.h"
#include "skeleton/level_set_graph.h"
#include "skeleton/voxel_graph.h"

namespace mcquad {
namespace {

constexpr size_t kFewestPoints = 200;
constexpr size_t kMostVoxels = 40000;
// A voxel a few times the nearest-neighbour spacing holds a few points even
// where the scan is sparsest (random points leave gaps several spacings wide).
constexpr double kSpacingsPerVoxel = 4.5;
// A spur whose tip is nearer its junction than this many junction radii is a
// bump (noise, a crease, the root's own cap), not a limb.
constexpr double kSpurRadii = 1.8;
// Or whose tip rises less than this many above the band where it splits off
// (fronts meeting on a loop leave such bulges; an open limb's rim rises its
// length above its junction, a capped one a radius more).
constexpr double kSpurRise = 1.5;
// Whatever the junction's radius, a spur is a limb when its tip sticks out of
// the ball inscribed at its junction by this many times its own radius (an
// elephant's arms and trunk leave a head and chest three to six times their
// width; a blunt end of a slab, a bump, 1.2 to 1.7 times).
constexpr double kLimbProtrusion = 2.0;
// A spur of two pieces is less evidence: it must stick out further (the
// elephant's second foot, 3.5 times its width; a sliver beside a hole in a
// Y's scan, 2.25 times).
constexpr double kShortLimbProtrusion = 3.0;
// A cycle of the level-set graph spanning less geodesic distance than this
// many tube radii needs more evidence that it is a handle (is_a_handle).
constexpr double kCycleRadii = 2.0;
// A ring wider than this many times its limb's median ring is a band that
// still spans a neighbouring limb, no part of this limb's axis.
constexpr double kWidestRing = 1.25;
// Next to a junction of radius r, out to this many r, a straight limb's
// rings are held to its outer axis (outer_axis_of_straight_limb): those off
// it by more than kOffOuterAxis of the limb's radius are bands spanning two
// limbs. A limb is straight when its rings from there on lie within
// kStraightLimb of its radius of one line (theta's arcs, bent, are not; at
// 0.15 of its radius the planar star of 7's arm did not count as straight).
constexpr double kOuterAxisRadii = 3.0, kOffOuterAxis = 0.25, kStraightLimb = 0.25;
// Two junction nodes whose link is shorter than this many times the wider
// ball inscribed at either are one branching region (place_junctions). At
// 1.0 the octopus kept 2 junctions for 1; 1.5 and 2.0 give the same table.
// (Against the ball at the link's middle, 1.5 merged two of the armadillo's
// junctions into a node outside its cloud; this test leaves the six scans'
// skeletons as they were.)
constexpr double kOneBodyBalls = 1.5;
// Pieces whose widest angular gap exceeds this are arcs, not rings.
constexpr double kArcGap = M_PI / 2;

//! Whether a piece of a band (a LevelSetNode, or a RingFit of a slice) goes
//! round its centre: a ring, not an arc.
template <typename Piece>
bool is_ring(const Piece& piece) {
  return piece.widest_gap <= kArcGap;
}

//! The level-set graph as an editable graph: nodes die, edges go.
struct WorkGraph {
  std::vector<std::set<int>> adjacent;
  std::vector<bool> alive;

  explicit WorkGraph(const LevelSetGraph& graph) : adjacent(graph.nodes.size()), alive(graph.nodes.size(), true) {
    for (auto [a, b] : graph.edges) {
      adjacent[size_t(a)].insert(b);
      adjacent[size_t(b)].insert(a);
    }
  }
  int degree(int v) const { return int(adjacent[size_t(v)].size()); }
  void remove_edge(int a, int b) {
    adjacent[size_t(a)].erase(b);
    adjacent[size_t(b)].erase(a);
  }
  void remove_node(int v) {
    for (int w : std::vector<int>(adjacent[size_t(v)].begin(), adjacent[size_t(v)].end())) remove_edge(v, w);
    alive[size_t(v)] = false;
  }
};

//! A chain of level-set nodes between two key nodes (degree other than 2),
//! both included; a closed chain starts and ends at the same node.
struct Chain {
  std::vector<int> nodes;
  bool closed() const { return nodes.front() == nodes.back(); }
};

struct Extraction {
  const VoxelGraph& voxels;
  const LevelSetGraph& levels;
  const PointIndex<double>& surface;                   // over surface_points
  const std::vector<Eigen::Vector3d>& surface_points;  // the kept voxels' centroids
  double band_width;
  WorkGraph work;
  std::vector<Eigen::Vector3d> position;  // per level-set node, moved as the skeleton is cleaned

  //! Distance from x to the surface: the radius of the ball inscribed there.
  double inscribed_radius(const Eigen::Vector3d& x) const { return std::sqrt(surface.nearest(x).second); }
  const LevelSetNode& node(int v) const { return levels.nodes[size_t(v)]; }
};

double chain_length(const Extraction& x, const std::vector<int>& nodes) {
  double length = 0;
  for (size_t k = 1; k < nodes.size(); ++k)
    length += (x.position[size_t(nodes[k])] - x.position[size_t(nodes[k - 1])]).norm();
  return length;
}

double median(std::vector<double> values) { return quantile_of(std::move(values), 0.5); }

//! Whether node v of a chain (`nodes`) is a ring of a cap: the chain runs to
//! an end, and v lies within its own radius of that end's tip. There the
//! bands of distance lean and their centres with them (the T's arm, four
//! radii long: its axis tilted 10 degrees, the junction 0.25 radii off).
bool in_a_cap(const Extraction& x, const std::vector<int>& nodes, int v) {
  return x.work.degree(nodes.back()) == 1 &&
         (x.position[size_t(v)] - x.position[size_t(nodes.back())]).norm() < x.node(v).radius;
}

//! The median radius of a chain's rings (arcs and the rings of a cap left
//! out); infinite when it has none, so that no ring is wider than a
//! multiple of it.
double median_ring_radius(const Extraction& x, const std::vector<int>& nodes) {
  std::vector<double> radii;
  for (int v : nodes)
    if (is_ring(x.node(v)) && !in_a_cap(x, nodes, v)) radii.push_back(x.node(v).radius);
  return radii.empty() ? INFINITY : median(radii);
}

//! Whether a cycle of the level-set graph is a handle, judged by its pieces
//! between the split and the merge. A handle's two branches are tubes of
//! their own, each band crossing them as a ring however short the hole
//! between them (a slab pierced by holes); around a hole in the scan or a
//! noisy patch one ring splits into arcs. A cycle spanning less geodesic
//! distance than kCycleRadii tube radii must be mostly rings on both
//! branches; a longer one (a loop round a torus with holes in its scan:
//! 8 rings in 17 pieces measured) at least a third of rings on each.
bool is_a_handle(const Extraction& x, const std::vector<int>& branch_a, const std::vector<int>& branch_b) {
  auto band_below = [&](int v, int w) { return x.node(v).band < x.node(w).band; };
  int merge = -1, split_band = std::numeric_limits<int>::max();
  std::vector<double> radii;  // the median: a cycle through a fat body has a few huge bands
  for (const auto* branch : {&branch_a, &branch_b})
    for (int v : *branch) {
      if (merge < 0 || band_below(merge, v)) merge = v;
      split_band = std::min(split_band, x.node(v).band - 1);
      radii.push_back(x.node(v).radius);
    }
  if (merge < 0) return false;
  auto count = [&](const std::vector<int>& branch) {
    std::array<size_t, 2> rings_pieces{0, 0};
    for (int v : branch)
      if (v != merge) {
        rings_pieces[0] += is_ring(x.node(v));
        ++rings_pieces[1];
      }
    return rings_pieces;
  };
  auto [rings_a, pieces_a] = count(branch_a);
  auto [rings_b, pieces_b] = count(branch_b);
  double span = double(x.node(merge).band - split_band + 1) * x.band_width;
  if (span >= kCycleRadii * median(radii)) return 3 * rings_a >= pieces_a && 3 * rings_b >= pieces_b;
  return 2 * rings_a >= pieces_a && 2 * rings_b >= pieces_b && 2 * (rings_a + rings_b) > pieces_a + pieces_b;
}

//! Removes the closing edge of every cycle of the spanning tree
//! (breadth-first, in node order) that is no handle.
void remove_false_cycles(Extraction& x) {
  size_t n = x.work.adjacent.size();
  std::vector<int> parent(n, -2);
  std::vector<std::array<int, 2>> closing;
  for (size_t start = 0; start < n; ++start) {
    if (!x.work.alive[start] || parent[start] != -2) continue;
    parent[start] = -1;
    std::vector<int> queue{int(start)};
    for (size_t head = 0; head < queue.size(); ++head) {
      int v = queue[head];
      for (int w : x.work.adjacent[size_t(v)]) {
        if (parent[size_t(w)] == -2) {
          parent[size_t(w)] = v;
          queue.push_back(w);
        } else if (w != parent[size_t(v)] && v < w) {
          closing.push_back({v, w});
        }
      }
    }
  }
  for (auto [a, b] : closing) {
    std::vector<int> up_a, up_b;
    for (int v = a; v >= 0; v = parent[size_t(v)]) up_a.push_back(v);
    std::set<int> on_a(up_a.begin(), up_a.end());
    int meet = b;
    for (; meet >= 0 && !on_a.count(meet); meet = parent[size_t(meet)]) up_b.push_back(meet);
    if (meet < 0) continue;
    up_a.erase(std::find(up_a.begin(), up_a.end(), meet), up_a.end());
    if (!is_a_handle(x, up_a, up_b)) x.work.remove_edge(a, b);
  }
}

//! From a node of degree 1, the nodes up to the first of another degree (included).
std::vector<int> walk_from_end(const Extraction& x, int end) {
  std::vector<int> path{end};
  int previous = -1, current = end;
  while (true) {
    int next = -1;
    for (int w : x.work.adjacent[size_t(current)])
      if (w != previous) next = w;
    if (next < 0) break;
    path.push_back(next);
    if (x.work.degree(next) != 2) break;
    previous = current;
    current = next;
  }
  return path;
}

//! The radius of a junction: the inscribed ball at its node or the widest of
//! its limbs next to it (rings two to eight along each), whichever is larger.
double junction_radius(const Extraction& x, const std::vector<std::vector<int>>& limbs, const Eigen::Vector3d& at) {
  double radius = x.inscribed_radius(at);
  for (const auto& nodes : limbs) {
    std::vector<double> radii;
    for (size_t k = 2; k < std::min<size_t>(nodes.size() - 1, 9); ++k) radii.push_back(x.node(nodes[k]).radius);
    radius = std::max(radius, median(radii));
  }
  return radius;
}

//! The radius a spur is judged by at its junction: the inscribed ball there,
//! or the thinnest of the junction's other limbs (the median of rings two to
//! eight along each), whichever is larger. Not the widest: next to a split
//! the rings can be two limbs wide.
double spur_radius(const Extraction& x, int junction, int spur_first) {
  double thinnest = std::numeric_limits<double>::max();
  for (int first : x.work.adjacent[size_t(junction)]) {
    if (first == spur_first) continue;
    std::vector<double> radii;
    int previous = junction, current = first;
    for (int k = 1; k <= 8; ++k) {
      if (k >= 2) radii.push_back(x.node(current).radius);
      if (x.work.degree(current) != 2) break;
      int next = *x.work.adjacent[size_t(current)].begin();
      if (next == previous) next = *x.work.adjacent[size_t(current)].rbegin();
      previous = current;
      current = next;
    }
    if (!radii.empty()) thinnest = std::min(thinnest, median(radii));
  }
  double inscribed = x.inscribed_radius(x.position[size_t(junction)]);
  return thinnest == std::numeric_limits<double>::max() ? inscribed : std::max(inscribed, thinnest);
}

//! Whether a spur (`path` from its tip to its junction) is a limb in its
//! own right: two pieces or more, mostly rings, whose tip sticks out of the
//! junction's inscribed ball by kLimbProtrusion times their median radius
//! (kShortLimbProtrusion for two pieces). The junction's radius alone
//! prunes thin limbs of a fat body.
bool is_a_limb(const Extraction& x, const std::vector<int>& path) {
  if (path.size() < 3) return false;
  std::vector<double> radii;
  size_t rings = 0;
  for (size_t k = 1; k + 1 < path.size(); ++k) {  // not the tip's cap, not the junction
    radii.push_back(x.node(path[k]).radius);
    rings += is_ring(x.node(path[k]));
  }
  const Eigen::Vector3d& tip = x.position[size_t(path.front())];
  const Eigen::Vector3d& junction = x.position[size_t(path.back())];
  double protrusion = (tip - junction).norm() - x.inscribed_radius(junction);
  double needed = path.size() == 3 ? kShortLimbProtrusion : kLimbProtrusion;
  return 2 * rings >= radii.size() && protrusion >= needed * median(radii);
}

//! Whether every piece of a spur (tip first) is wider than the one before,
//! up to the junction: a cap of the body with no stretch of tube, as the
//! bands round a frame's corner grow from the root there (0.42 to 1.89
//! tube radii), where a limb's rings stay at its radius past its cap.
bool widens_all_the_way(const Extraction& x, const std::vector<int>& path) {
  for (size_t k = 1; k < path.size(); ++k)
    if (x.node(path[k]).radius <= x.node(path[k - 1]).radius) return false;
  return path.size() >= 3;
}

//! Whether a spur is short for its junction: its tip within kSpurRadii
//! junction radii of it, or within 2.5 and rising less than kSpurRise
//! above it or widening all the way; or a single piece that is an arc (a
//! sliver of a band beside the junction, e.g. along a palm's edge), however
//! far it reaches.
bool is_a_bump(const Extraction& x, const std::vector<int>& path) {
  int tip = path.front(), junction = path.back();
  double reach = (x.position[size_t(tip)] - x.position[size_t(junction)]).norm();
  double rise = std::abs(x.node(tip).band - x.node(junction).band) * x.band_width;
  double radius = spur_radius(x, junction, path[path.size() - 2]);
  bool short_spur = reach < kSpurRadii * radius || (rise < kSpurRise * radius && reach < 2.5 * radius);
  bool sliver = path.size() == 2 && !is_ring(x.node(tip));
  return short_spur || sliver || (reach < 2.5 * radius && widens_all_the_way(x, path));
}

//! Whether the two spurs of a junction of degree 3 are the tips of two
//! limbs that part only at their caps (two arms of a star 16 degrees apart):
//! both bumps, tips 1.5 of the junction's ring radii apart or more, and one
//! of them a tube narrower than the band they split from (a ring at most
//! 0.7 of its radius). An open rim splits into two arcs as wide as the tube,
//! and a crease's bump has a limb for a sibling: neither is a fork.
bool is_a_late_fork(const Extraction& x, int junction, const std::vector<std::vector<int>>& spurs) {
  if (x.work.degree(junction) != 3 || spurs.size() != 2 || !is_ring(x.node(junction))) return false;
  const double band = x.node(junction).radius;
  bool narrower = false;
  for (const auto& spur : spurs) {
    if (!is_a_bump(x, spur) || is_a_limb(x, spur)) return false;
    for (size_t k = 0; k + 1 < spur.size(); ++k)
      narrower |= is_ring(x.node(spur[k])) && x.node(spur[k]).radius <= 0.7 * band;
  }
  const double apart = (x.position[size_t(spurs[0].front())] - x.position[size_t(spurs[1].front())]).norm();
  return narrower && apart >= 1.5 * band;
}

//! Prunes spurs that are bumps and not limbs, the shortest at each junction
//! first, until none is left.
void prune_spurs(Extraction& x) {
  for (bool changed = true; changed;) {
    changed = false;
    std::map<int, std::vector<std::vector<int>>> spurs;  // per junction, each from its tip, in tip order
    for (size_t v = 0; v < x.work.adjacent.size(); ++v)
      if (x.work.alive[v] && x.work.degree(int(v)) == 1) {
        std::vector<int> path = walk_from_end(x, int(v));
        spurs[path.back()].push_back(std::move(path));
      }
    std::map<int, std::pair<double, std::vector<int>>> shortest;  // per junction
    for (const auto& [junction, paths] : spurs) {
      if (x.work.degree(junction) < 3 || is_a_late_fork(x, junction, paths)) continue;
      for (const auto& path : paths) {
        if (!is_a_bump(x, path) || is_a_limb(x, path)) continue;
        double reach = (x.position[size_t(path.front())] - x.position[size_t(junction)]).norm();
        auto found = shortest.find(junction);
        if (found == shortest.end() || reach < found->second.first) shortest[junction] = {reach, path};
      }
    }
    for (auto& [junction, spur] : shortest) {
      for (size_t k = 0; k + 1 < spur.second.size(); ++k) x.work.remove_node(spur.second[k]);
      changed = true;
    }
  }
}

std::vector<Chain> trace_chains(const Extraction& x) {
  std::vector<Chain> chains;
  std::set<std::array<int, 2>> used;  // directed first steps
  size_t n = x.work.adjacent.size();
  std::vector<bool> visited(n, false);
  auto walk = [&](int key, int first) {
    Chain chain{{key, first}};
    visited[size_t(key)] = visited[size_t(first)] = true;
    int previous = key, current = first;
    while (x.work.degree(current) == 2 && current != key) {
      int next = *x.work.adjacent[size_t(current)].begin();
      if (next == previous) next = *x.work.adjacent[size_t(current)].rbegin();
      previous = current;
      current = next;
      chain.nodes.push_back(current);
      visited[size_t(current)] = true;
    }
    used.insert({chain.nodes.back(), chain.nodes[chain.nodes.size() - 2]});
    return chain;
  };
  for (size_t v = 0; v < n; ++v) {
    if (!x.work.alive[v] || x.work.degree(int(v)) == 2 || x.work.degree(int(v)) == 0) continue;
    for (int w : x.work.adjacent[v]) {
      if (used.count({int(v), w})) continue;
      used.insert({int(v), w});
      chains.push_back(walk(int(v), w));
    }
  }
  // Pure loops of regular nodes, each from its roundest piece: the loop's
  // first node is its key node, which the cross sections do not move, and
  // where the root lies on the loop its piece is a patch, not a ring.
  for (size_t v = 0; v < n; ++v) {
    if (!x.work.alive[v] || visited[v] || x.work.degree(int(v)) != 2) continue;
    int start = int(v), previous = -1, current = int(v);
    do {
      if (x.node(current).widest_gap < x.node(start).widest_gap) start = current;
      int next = *x.work.adjacent[size_t(current)].begin();
      if (next == previous) next = *x.work.adjacent[size_t(current)].rbegin();
      previous = current;
      current = next;
    } while (current != int(v) && x.work.degree(current) == 2);
    chains.push_back(walk(start, *x.work.adjacent[size_t(start)].begin()));
  }
  return chains;
}

//! Moves every inner node of a chain whose piece is an arc (the bands
//! around the root, where they start as a patch on one side of the tube;
//! next to a junction, where a band spans a corner) and lies more than half
//! a radius off the straight line between the nearest anchors on either
//! side onto that line: an arc's circle can lie off the tube altogether (a
//! frame's edge: 1.9 radii out). Anchors are the inner ring nodes and, once
//! the junctions are placed (`from_junctions`), the junction nodes.
void bridge_arcs(Extraction& x, const std::vector<int>& nodes, bool from_junctions) {
  auto is_anchor = [&](size_t k) {
    if (k == 0 || k + 1 == nodes.size()) return from_junctions && x.work.degree(nodes[k]) >= 3;
    return is_ring(x.node(nodes[k]));
  };
  const size_t first = from_junctions ? 0 : 1, last = from_junctions ? nodes.size() - 1 : nodes.size() - 2;
  for (size_t k = 1; k + 1 < nodes.size(); ++k) {
    if (is_ring(x.node(nodes[k]))) continue;
    size_t before = k, after = k;
    while (before > first && !is_anchor(before)) --before;
    while (after < last && !is_anchor(after)) ++after;
    if (!is_anchor(before) || !is_anchor(after) || before == k || after == k) continue;
    double t = double(k - before) / double(after - before);
    Eigen::Vector3d bridged = (1 - t) * x.position[size_t(nodes[before])] + t * x.position[size_t(nodes[after])];
    double r = 0.5 * (x.node(nodes[before]).radius + x.node(nodes[after]).radius);
    if ((x.position[size_t(nodes[k])] - bridged).norm() > 0.5 * r) x.position[size_t(nodes[k])] = bridged;
  }
}

//! Moves every inner ring of a chain onto the centre of the tube's cross
//! section there: a band of geodesic distance crosses a tube at a slant and
//! warped where a limb branches off or the tube bends, and its centre leans;
//! the slice perpendicular to the chain does not. Twice, since the chain's
//! tangent improves with its nodes.
void centre_on_cross_sections(Extraction& x, const std::vector<Chain>& chains) {
  const double half_slab = 0.75 * x.voxels.voxel_size;
  const VoxelGraph& graph = x.voxels;
  std::vector<Eigen::Vector3d> slice;
  std::vector<uint32_t> reached;
  std::vector<char> seen(graph.size(), 0);
  for (const auto& chain : chains) bridge_arcs(x, chain.nodes, false);
  for (int pass = 0; pass < 2; ++pass) {
    for (const auto& chain : chains) {
      const std::vector<int>& nodes = chain.nodes;
      std::vector<Eigen::Vector3d> moved(nodes.size());
      for (size_t k = 1; k + 1 < nodes.size(); ++k) {
        const Eigen::Vector3d& p = x.position[size_t(nodes[k])];
        moved[k] = p;
        size_t back = k >= 2 ? k - 2 : k - 1, ahead = std::min(k + 2, nodes.size() - 1);
        Eigen::Vector3d tangent = x.position[size_t(nodes[ahead])] - x.position[size_t(nodes[back])];
        double r = x.node(nodes[k]).radius;
        if (tangent.norm() <= 0 || r <= 0) continue;
        tangent.normalize();
        // The surface around this ring only: what the ring's own voxels reach
        // within the ball, not another tube passing close by.
        const double ball2 = (1.6 * r) * (1.6 * r);
        reached.clear();
        for (uint32_t v : x.node(nodes[k]).voxels)
          if ((graph.centroids[v] - p).squaredNorm() <= ball2 && !seen[v]) {
            seen[v] = 1;
            reached.push_back(v);
          }
        for (size_t head = 0; head < reached.size(); ++head)
          for (uint32_t e = graph.offsets[reached[head]]; e < graph.offsets[reached[head] + 1]; ++e) {
            uint32_t w = graph.neighbours[e];
            if (!seen[w] && (graph.centroids[w] - p).squaredNorm() <= ball2) {
              seen[w] = 1;
              reached.push_back(w);
            }
          }
        slice.clear();
        for (uint32_t v : reached) {
          seen[v] = 0;
          if (std::abs((graph.centroids[v] - p).dot(tangent)) <= half_slab) slice.push_back(graph.centroids[v]);
        }
        RingFit ring = fit_ring(slice);
        Eigen::Vector3d shift = ring.centre - p;
        shift -= shift.dot(tangent) * tangent;  // stay in the slice
        if (is_ring(ring) && shift.norm() < 0.5 * r) moved[k] = p + shift;
      }
      for (size_t k = 1; k + 1 < nodes.size(); ++k) x.position[size_t(nodes[k])] = moved[k];
    }
  }
}

struct Line {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;  //!< unit, pointing away from the key node the line was fitted from
};

//! The axis of a chain near one of its ends (`nodes` start there): the
//! tangent, at the first ring whose distance from `from` is at least `near`,
//! of a parabola through the ring centres up to `far` (a line through fewer
//! than four), arcs and the rings of a cap (in_a_cap) left out. The tangent
//! rather than a mean line, so that a limb curving away from its junction
//! does not throw the junction off. Rings wider than `widest` are left out
//! too. None when fewer than two
//! rings qualify.
bool fit_axis(const Extraction& x, const std::vector<int>& nodes, const Eigen::Vector3d& from, double near, double far,
              Line& line, double widest = INFINITY) {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> along;
  double walked = 0;
  for (size_t k = 1; k + 1 < nodes.size(); ++k) {
    const Eigen::Vector3d& p = x.position[size_t(nodes[k])];
    double distance = (p - from).norm();
    if (distance > far) break;
    if (distance < near || !is_ring(x.node(nodes[k])) || x.node(nodes[k]).radius > widest) continue;
    if (in_a_cap(x, nodes, nodes[k])) continue;
    if (!points.empty()) walked += (p - points.back()).norm();
    points.push_back(p);
    along.push_back(walked);
  }
  if (points.size() < 2 || walked <= 0) return false;
  // A parabola only where the rings bend away from their mean line.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= double(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& p : points) covariance += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  double off_line = std::sqrt(std::max(0.0, eigen.eigenvalues()(0) + eigen.eigenvalues()(1)) / double(points.size()));
  double ring_radius = x.node(nodes[1]).radius;
  if (points.size() < 4 || off_line < 0.05 * ring_radius) {
    Eigen::Vector3d direction = eigen.eigenvectors().col(2);
    if (direction.dot(points.back() - points.front()) < 0) direction = -direction;
    line = {mean, direction};
    return true;
  }
  int terms = 3;
  Eigen::MatrixXd basis(points.size(), terms);
  Eigen::MatrixXd values(points.size(), 3);
  for (size_t k = 0; k < points.size(); ++k) {
    double s = along[k] / walked;  // scaled to [0, 1] for a well-conditioned fit
    basis(long(k), 0) = 1;
    basis(long(k), 1) = s;
    if (terms == 3) basis(long(k), 2) = s * s;
    values.row(long(k)) = points[k].transpose();
  }
  Eigen::MatrixXd coefficients = basis.colPivHouseholderQr().solve(values);
  Eigen::Vector3d direction = coefficients.row(1).transpose();
  if (!direction.allFinite() || direction.norm() <= 0) return false;
  line = {coefficients.row(0).transpose(), direction.normalized()};
  return true;
}

//! The distance from `p` to `line`.
double distance_from_line(const Line& line, const Eigen::Vector3d& p) {
  Eigen::Vector3d d = p - line.point;
  return (d - d.dot(line.direction) * line.direction).norm();
}

//! Whether a limb (`nodes`, from its junction at `centre` of radius `r`) is
//! straight beyond kOuterAxisRadii r: a line fitted to its rings from there
//! to four radii farther (none wider than `widest`) passes within
//! kStraightLimb of the limb's radius of every one of them. The line goes to
//! `axis`.
bool outer_axis_of_straight_limb(const Extraction& x, const std::vector<int>& nodes, const Eigen::Vector3d& centre,
                                 double r, double limb_radius, double widest, Line& axis) {
  const double near = kOuterAxisRadii * r, far = near + 4 * r;
  if (!(limb_radius > 0) || !std::isfinite(limb_radius) || !fit_axis(x, nodes, centre, near, far, axis, widest))
    return false;
  for (int v : nodes) {
    const Eigen::Vector3d& p = x.position[size_t(v)];
    const double distance = (p - centre).norm();
    if (distance >= near && distance <= far && is_ring(x.node(v)) &&
        distance_from_line(axis, p) > kStraightLimb * limb_radius)
      return false;
  }
  return true;
}

//! The point nearest all lines in the least-squares sense, pulled weakly
//! toward `start` (so that nearly parallel limbs do not throw it far).
Eigen::Vector3d nearest_to_lines(const std::vector<Line>& lines, const Eigen::Vector3d& start) {
  const double pull = 0.05;
  Eigen::Matrix3d a = pull * Eigen::Matrix3d::Identity();
  Eigen::Vector3d b = pull * start;
  for (const auto& line : lines) {
    Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - line.direction * line.direction.transpose();
    a += across;
    b += across * line.point;
  }
  return a.ldlt().solve(b);
}

std::vector<int> reversed(std::vector<int> nodes) {
  std::reverse(nodes.begin(), nodes.end());
  return nodes;
}

//! Junctions: nearby junction nodes of one branching region merged, each
//! moved to where its limbs' axes meet, and the rings inside it dropped.
void place_junctions(Extraction& x, std::vector<Chain>& chains) {
  size_t n = x.work.adjacent.size();
  auto is_junction = [&](int v) { return x.work.degree(v) >= 3; };

  // Each chain seen from each of its junction ends.
  struct Limb {
    size_t chain;
    bool from_front;
    std::vector<int> nodes;  // starting at the junction
  };
  auto limbs_of = [&](const std::set<int>& cluster, const std::set<size_t>& internal) {
    std::vector<Limb> limbs;
    for (size_t c = 0; c < chains.size(); ++c) {
      if (internal.count(c)) continue;
      if (cluster.count(chains[c].nodes.front())) limbs.push_back({c, true, chains[c].nodes});
      if (cluster.count(chains[c].nodes.back())) limbs.push_back({c, false, reversed(chains[c].nodes)});
    }
    return limbs;
  };
  // The axes of the limbs, each fitted from its own junction node. Limbs
  // shorter than two radii (links to a neighbouring junction node of the
  // same region, mostly) have no axis worth the name. Rings much wider than
  // their limb (kWidestRing) are left out on request only (meeting_point);
  // whether two junction nodes are one region is judged with them (left out
  // there, the tail-loop's two junctions became one).
  auto limb_axes = [&](const std::vector<Limb>& limbs, double r, bool leave_out_wide_rings = false) {
    std::vector<Line> lines;
    size_t long_limbs = 0;
    for (const auto& limb : limbs) long_limbs += chain_length(x, limb.nodes) >= 2 * r;
    for (const auto& limb : limbs) {
      if (long_limbs >= 2 && chain_length(x, limb.nodes) < 2 * r) continue;
      const Eigen::Vector3d& from = x.position[size_t(limb.nodes.front())];
      const double widest = leave_out_wide_rings ? kWidestRing * median_ring_radius(x, limb.nodes) : INFINITY;
      Line line;
      if (fit_axis(x, limb.nodes, from, r, 3 * r, line, widest) ||
          fit_axis(x, limb.nodes, from, 0.5 * r, 5 * r, line, widest))
        lines.push_back(line);
    }
    return lines;
  };
  // Where the axes of a narrow fork meet can be several radii from where its
  // bands split; beyond four radii they are not axes. Where they meet
  // outside the body, bands still spanning two limbs of a narrow fork may
  // have thrown an axis (the 30-degree Y's arm: its axis came out across the
  // fork, the junction 3.5 radii up the wider arm): fitted again without the
  // rings much wider than their limb, the axes may meet inside. (Always
  // leaving those rings out moved the aorta's junction 1.3 radii up its
  // trunk: its iliacs bend away from the hub.) Otherwise (tangents of limbs
  // that bend away from the hub, as a theta's arcs leave its poles) the
  // junction is the deepest point between the band's centre and where the
  // axes meet.
  auto meet_inside = [&](const std::vector<Line>& lines, const Eigen::Vector3d& start, double r) {
    Eigen::Vector3d meet = nearest_to_lines(lines, start);
    return std::make_pair(meet, (meet - start).norm() < 4 * r && x.inscribed_radius(meet) >= 0.5 * r);
  };
  auto meeting_point = [&](const std::vector<Limb>& limbs, const Eigen::Vector3d& start, double r) {
    std::vector<Line> lines = limb_axes(limbs, r);
    if (lines.size() < 2) return start;
    auto [meet, inside] = meet_inside(lines, start, r);
    if (inside) return meet;
    std::vector<Line> narrow = limb_axes(limbs, r, true);
    if (narrow.size() >= 2) {
      auto [again, inside_again] = meet_inside(narrow, start, r);
      if (inside_again) return again;
    }
    if ((meet - start).norm() >= 4 * r) return start;
    Eigen::Vector3d deepest = start;
    double depth = x.inscribed_radius(start);
    constexpr int kSteps = 16;
    for (int k = 1; k < kSteps; ++k) {
      Eigen::Vector3d p = start + (meet - start) * (double(k) / kSteps);
      double d = x.inscribed_radius(p);
      if (d > depth) {
        depth = d;
        deepest = p;
      }
    }
    return deepest;
  };
  auto farthest_axis = [](const std::vector<Line>& lines, const Eigen::Vector3d& p) {
    double farthest = 0;
    for (const auto& line : lines) farthest = std::max(farthest, distance_from_line(line, p));
    return farthest;
  };

  // One point for many axes: all within half a radius of it, inside the
  // body. A hub of five limbs or more may have one thin limb whose axis,
  // fitted where it leaves the hub, is off by more; it may miss by up to a
  // radius when the others meet without it.
  auto axes_meet_at_one_point = [&](std::vector<Line> lines, const Eigen::Vector3d& start, double r) {
    Eigen::Vector3d meet = nearest_to_lines(lines, start);
    if (farthest_axis(lines, meet) < 0.5 * r) return x.inscribed_radius(meet) >= 0.5 * r;
    if (lines.size() < 5) return false;
    auto distance = [&](const Line& line) { return distance_from_line(line, meet); };
    auto worst = std::max_element(lines.begin(), lines.end(),
                                  [&](const Line& p, const Line& q) { return distance(p) < distance(q); });
    Line outlier = *worst;
    lines.erase(worst);
    meet = nearest_to_lines(lines, start);
    return farthest_axis(lines, meet) < 0.5 * r && farthest_axis({outlier}, meet) < r &&
           x.inscribed_radius(meet) >= 0.5 * r;
  };

  UnionFind regions(n);
  std::vector<double> radius(n, 0);
  for (size_t v = 0; v < n; ++v) {
    if (!x.work.alive[v] || !is_junction(int(v))) continue;
    std::vector<std::vector<int>> limb_nodes;
    for (const auto& limb : limbs_of({int(v)}, {})) limb_nodes.push_back(limb.nodes);
    radius[v] = junction_radius(x, limb_nodes, x.position[v]);
  }
  // Chains between the regions of a and b: two or more close a cycle that
  // remove_false_cycles kept as a handle, which joining would collapse.
  auto links_between = [&](int a, int b) {
    size_t ra = regions.find(size_t(a)), rb = regions.find(size_t(b)), links = 0;
    for (const auto& chain : chains) {
      size_t front = regions.find(size_t(chain.nodes.front())), back = regions.find(size_t(chain.nodes.back()));
      links += (front == ra && back == rb) || (front == rb && back == ra);
    }
    return links;
  };
  // Two junction nodes joined by a short chain are one branching region when
  // the axes of all their other limbs pass through one point (within half a
  // radius); two junctions a short bone apart (the double-junction shape)
  // have axes meeting at two points. Or when the chain is shorter than
  // kOneBodyBalls times the wider of the balls inscribed at its ends: both
  // lie in one body, whatever their limbs' axes do (an octopus's curling arms
  // leave its mantle with tangents meeting nowhere: 5 junction nodes for 1).
  for (size_t c = 0; c < chains.size(); ++c) {
    int a = chains[c].nodes.front(), b = chains[c].nodes.back();
    if (a == b || !is_junction(a) || !is_junction(b) || links_between(a, b) > 1) continue;
    double r = std::max(radius[size_t(a)], radius[size_t(b)]);
    double length = chain_length(x, chains[c].nodes);
    if (length >= 4 * r) continue;
    std::vector<Line> lines = limb_axes(limbs_of({a, b}, {c}), r);
    Eigen::Vector3d middle = 0.5 * (x.position[size_t(a)] + x.position[size_t(b)]);
    Eigen::Vector3d meet = lines.size() >= 2 ? nearest_to_lines(lines, middle) : middle;
    bool one_point =
        lines.size() >= 2 && farthest_axis(lines, meet) < 0.5 * r && (meet - middle).norm() < 0.5 * length + r;
    const double ball = std::max(x.inscribed_radius(x.position[size_t(a)]), x.inscribed_radius(x.position[size_t(b)]));
    const bool in_one_body = length < kOneBodyBalls * ball;
    if (length < 0.5 * r || one_point || in_one_body) regions.join(size_t(a), size_t(b));
  }
  // Then whole regions: two regions a link apart are one when the axes of
  // all their outer limbs meet at one point. A hub of many limbs splits into
  // several junction nodes, and a pair of them sees only its own limbs; arms
  // close in angle part late, so their link may run up to eight radii.
  auto members_of = [&](size_t a, size_t b) {
    std::set<int> members;
    for (size_t v = 0; v < n; ++v)
      if (x.work.alive[v] && is_junction(int(v)) &&
          (regions.find(v) == regions.find(a) || regions.find(v) == regions.find(b)))
        members.insert(int(v));
    return members;
  };
  for (int pass = 0; pass < 2; ++pass)
    for (size_t c = 0; c < chains.size(); ++c) {
      int a = chains[c].nodes.front(), b = chains[c].nodes.back();
      if (a == b || !is_junction(a) || !is_junction(b) || regions.find(size_t(a)) == regions.find(size_t(b)) ||
          links_between(a, b) > 1)
        continue;
      std::set<int> members = members_of(size_t(a), size_t(b));
      double r = 0;
      Eigen::Vector3d middle = Eigen::Vector3d::Zero();
      for (int v : members) {
        r = std::max(r, radius[size_t(v)]);
        middle += x.position[size_t(v)] / double(members.size());
      }
      if (chain_length(x, chains[c].nodes) >= 8 * r) continue;
      std::set<size_t> links;
      for (size_t k = 0; k < chains.size(); ++k)
        if (members.count(chains[k].nodes.front()) && members.count(chains[k].nodes.back())) links.insert(k);
      std::vector<Line> lines = limb_axes(limbs_of(members, links), r);
      if (lines.size() < 3) continue;
      if (axes_meet_at_one_point(lines, middle, r)) regions.join(size_t(a), size_t(b));
    }
  std::map<int, std::set<int>> clusters;
  for (size_t v = 0; v < n; ++v)
    if (x.work.alive[v] && is_junction(int(v))) clusters[int(regions.find(v))].insert(int(v));

  // Rings a cycle's chain must keep however near its junctions they lie: two
  // on a loop back to its own node, one on each of two parallel chains, so
  // that the handle stays a cycle of distinct bones. (A link between two
  // nodes of one region is no handle: it goes.)
  std::vector<size_t> rings_to_keep(chains.size(), 0);
  for (size_t c = 0; c < chains.size(); ++c) {
    int a = chains[c].nodes.front(), b = chains[c].nodes.back();
    if (a == b)
      rings_to_keep[c] = 2;
    else if (regions.find(size_t(a)) != regions.find(size_t(b)) && links_between(a, b) > 1)
      rings_to_keep[c] = 1;
  }
  std::set<size_t> dropped;
  for (auto& [leader, members] : clusters) {
    double r = 0;
    Eigen::Vector3d start = Eigen::Vector3d::Zero();
    for (int v : members) {
      r = std::max(r, radius[size_t(v)]);
      start += x.position[size_t(v)];
    }
    start /= double(members.size());
    std::set<size_t> internal;
    for (size_t c = 0; c < chains.size(); ++c)
      if (members.count(chains[c].nodes.front()) && members.count(chains[c].nodes.back()) &&
          (members.size() > 1 || chains[c].closed()) && chain_length(x, chains[c].nodes) < 2 * r)
        internal.insert(c);
    std::vector<Limb> limbs = limbs_of(members, internal);
    Eigen::Vector3d centre = meeting_point(limbs, start, r);
    // Every member becomes the leader; the leader moves to the centre.
    x.position[size_t(leader)] = centre;
    for (size_t c : internal) dropped.insert(c);
    for (auto& chain : chains) {
      if (members.count(chain.nodes.front())) chain.nodes.front() = leader;
      if (members.count(chain.nodes.back())) chain.nodes.back() = leader;
    }
    // Drop the rings inside the junction: those not at least 0.75 r out along
    // their limb or within 1.5 r of its centre (the crotch bends them).
    for (const auto& limb : limbs) {
      std::vector<int>& nodes = chains[limb.chain].nodes;
      const double limb_radius = median_ring_radius(x, limb.nodes);
      const double widest = kWidestRing * limb_radius;
      Line axis;
      bool has_axis = fit_axis(x, limb.nodes, start, r, 3 * r, axis, widest) ||
                      fit_axis(x, limb.nodes, start, 0.5 * r, 5 * r, axis, widest);
      Eigen::Vector3d out = has_axis ? axis.direction : (x.position[size_t(limb.nodes.back())] - centre).normalized();
      size_t inner = 1;
      // Also, within 2.5 r of the centre, off the limb's own axis by more
      // than half its radius: a band still spanning this limb and its
      // neighbour, which have not parted yet (a fan's branches 30 degrees
      // apart: its hub node was 0.95 radii off).
      auto off_axis = [&](const Eigen::Vector3d& p) {
        if (!has_axis || limb_radius <= 0 || (p - centre).norm() > 2.5 * r) return false;
        return distance_from_line(axis, p) > 0.5 * limb_radius;
      };
      // And, for a straight limb, rings out to kOuterAxisRadii r off the line
      // through its rings beyond by more than a quarter of its radius: a band
      // still spanning two limbs whose shared stretch bent the near axis
      // toward it (the planar star of 7: a ring 0.5 of the smallest radius
      // off, between arms 34 degrees apart).
      Line outer_axis;
      const bool straight = outer_axis_of_straight_limb(x, limb.nodes, centre, r, limb_radius, widest, outer_axis);
      auto off_outer_axis = [&](const Eigen::Vector3d& p) {
        return straight && (p - centre).norm() <= kOuterAxisRadii * r &&
               distance_from_line(outer_axis, p) > kOffOuterAxis * limb_radius;
      };
      // And rings much wider than the limb: bands spanning it and a
      // neighbour (the rings fit_axis leaves out).
      auto inside = [&](int v) {
        const Eigen::Vector3d& p = x.position[size_t(v)];
        return (p - centre).dot(out) < 0.75 * r || (p - centre).norm() < 1.5 * r || off_axis(p) || off_outer_axis(p) ||
               x.node(v).radius > widest;
      };
      while (inner + 1 < limb.nodes.size() && inside(limb.nodes[inner])) ++inner;
      // limb.nodes[1 .. inner) are inside; erase them from the chain's matching
      // end (the other end may have been trimmed already), but at most half
      // of the inner rings beyond those the chain must keep.
      size_t keep = rings_to_keep[limb.chain];
      size_t count = std::min(inner - 1, nodes.size() - 2);
      if (keep > 0) count = std::min(count, nodes.size() - 2 >= keep ? (nodes.size() - 2 - keep) / 2 : 0);
      if (count == 0 || nodes.size() < 3) continue;
      if (limb.from_front)
        nodes.erase(nodes.begin() + 1, nodes.begin() + 1 + long(count));
      else
        nodes.erase(nodes.end() - 1 - long(count), nodes.end() - 1);
    }
  }
  std::vector<Chain> kept;
  for (size_t c = 0; c < chains.size(); ++c)
    if (!dropped.count(c)) kept.push_back(std::move(chains[c]));
  chains = std::move(kept);
}

//! Where a capped limb with no axis of its own ends: the tip is the voxel
//! near it farthest from the chain's other end `other`, and the end the
//! first point on the way back from it toward `other` whose inscribed ball
//! is nearly as wide as any within three radii: the centre of the ball
//! touching the tip, where the medial axis begins. Sets `axis` (from the
//! tip, pointing back) and `end` (along -axis.direction) as place_end uses them.
void medial_end(const Extraction& x, const std::vector<Eigen::Vector3d>& near_tip, const Eigen::Vector3d& other,
                double r, Line& axis, double& end) {
  if (near_tip.empty()) return;
  Eigen::Vector3d tip = near_tip.front();
  for (const auto& p : near_tip)
    if ((p - other).squaredNorm() > (tip - other).squaredNorm()) tip = p;
  Eigen::Vector3d back = other - tip;
  if (back.norm() <= 0) return;
  back.normalize();
  const double step = 0.05 * r, reach = std::min(3 * r, (other - tip).norm());
  std::vector<double> inscribed;
  for (double t = 0; t <= reach; t += step) inscribed.push_back(x.inscribed_radius(tip + t * back));
  const double widest = *std::max_element(inscribed.begin(), inscribed.end());
  size_t k = 0;
  while (k + 1 < inscribed.size() && inscribed[k] < 0.95 * widest) ++k;
  axis = {tip, back};
  end = -double(k) * step;
}

//! Moves an end node from the tip's last ring to the axis, one tube radius
//! in from a capped tip (where a capsule's end sits) or at an open rim; a
//! capped limb with too few rings for an axis ends where medial_end says.
void place_end(Extraction& x, std::vector<int>& nodes) {  // nodes start at the end
  std::vector<double> radii;
  const Eigen::Vector3d tip_ring = x.position[size_t(nodes.front())];
  for (size_t k = 1; k + 1 < nodes.size(); ++k) {
    if ((x.position[size_t(nodes[k])] - tip_ring).norm() > 6 * x.node(nodes[k]).radius) break;
    if (is_ring(x.node(nodes[k]))) radii.push_back(x.node(nodes[k]).radius);
  }
  double r = median(radii);
  if (r <= 0) return;
  Line axis;
  // A limb that parts from its neighbour only near its tip (two arms of a
  // star 18 degrees apart) has too few rings for an axis: the line from its
  // other end to the tip's ring stands in (the ends had stayed at the caps'
  // last rings, up to 1.6 radii past the capsules' ends); capped, such a
  // limb then ends where its medial axis begins (the tip's last piece can
  // lie to one side of the apex, and the line through it with it).
  const bool has_axis =
      fit_axis(x, nodes, tip_ring, r, 3 * r, axis) || fit_axis(x, nodes, tip_ring, 0.3 * r, 4 * r, axis);
  if (!has_axis) {
    Eigen::Vector3d inward = x.position[size_t(nodes.back())] - tip_ring;
    if (nodes.size() < 2 || inward.norm() <= 0) return;
    axis = {tip_ring, inward.normalized()};
  }
  Eigen::Vector3d out = -axis.direction;
  // The tip: the farthest voxel along the axis among the rings near the end.
  std::vector<Eigen::Vector3d> near_tip;
  for (int v : nodes) {
    if ((x.position[size_t(v)] - tip_ring).norm() > 2 * r) break;
    for (uint32_t voxel : x.node(v).voxels) near_tip.push_back(x.voxels.centroids[voxel]);
  }
  double tip = -std::numeric_limits<double>::max();
  for (const auto& p : near_tip) tip = std::max(tip, (p - axis.point).dot(out));
  double spread = 0;
  int in_slab = 0;
  for (const auto& p : near_tip) {
    double along = (p - axis.point).dot(out);
    if (along < tip - 0.3 * r) continue;
    spread += (p - axis.point - along * out).norm();
    ++in_slab;
  }
  bool open = in_slab > 0 && spread / in_slab > 0.75 * r;
  double end = open ? tip : tip - r;
  if (!has_axis && !open) {
    medial_end(x, near_tip, x.position[size_t(nodes.back())], r, axis, end);
    out = -axis.direction;
  }
  // Drop the rings past (or within half a radius of) the new end.
  size_t keep_from = 1;
  while (keep_from + 1 < nodes.size() && (x.position[size_t(nodes[keep_from])] - axis.point).dot(out) > end - 0.5 * r)
    ++keep_from;
  nodes.erase(nodes.begin() + 1, nodes.begin() + long(keep_from));
  x.position[size_t(nodes.front())] = axis.point + end * out;
}

//! Douglas-Peucker on a chain's node positions, tolerance a tenth of its
//! median ring radius; at least `fewest_inner` inner nodes are kept (a loop
//! needs two, a second chain between the same two nodes one).
std::vector<int> thin_chain(const Extraction& x, const std::vector<int>& nodes, size_t fewest_inner) {
  std::vector<double> radii;
  radii.reserve(nodes.size());
  for (int v : nodes) radii.push_back(x.node(v).radius);
  double tolerance = 0.1 * median(radii);
  std::vector<bool> keep(nodes.size(), false);
  keep.front() = keep.back() = true;
  std::function<void(size_t, size_t)> split = [&](size_t first, size_t last) {
    if (last <= first + 1) return;
    const Eigen::Vector3d& a = x.position[size_t(nodes[first])];
    const Eigen::Vector3d& b = x.position[size_t(nodes[last])];
    double worst = -1;
    size_t worst_at = first;
    for (size_t k = first + 1; k < last; ++k) {
      const Eigen::Vector3d& p = x.position[size_t(nodes[k])];
      Eigen::Vector3d ab = b - a;
      double t = ab.squaredNorm() > 0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      double d = (p - a - t * ab).norm();
      if (d > worst) {
        worst = d;
        worst_at = k;
      }
    }
    if (worst > tolerance) {
      keep[worst_at] = true;
      split(first, worst_at);
      split(worst_at, last);
    }
  };
  split(0, nodes.size() - 1);
  size_t inner = size_t(std::count(keep.begin() + 1, keep.end() - 1, true));
  for (size_t k = 1; inner < fewest_inner && k <= fewest_inner && nodes.size() > 2; ++k) {
    size_t at = k * (nodes.size() - 1) / (fewest_inner + 1);
    if (at > 0 && at + 1 < nodes.size() && !keep[at]) {
      keep[at] = true;
      ++inner;
    }
  }
  std::vector<int> thinned;
  for (size_t k = 0; k < nodes.size(); ++k)
    if (keep[k]) thinned.push_back(nodes[k]);
  return thinned;
}

//! Fraction (by voxels) of the level-set pieces that are arcs rather than
//! rings: most of a sheet's, few of a tube's (rims and holes make some).
double arc_fraction(const LevelSetGraph& levels) {
  size_t arcs = 0, all = 0;
  for (const auto& node : levels.nodes) {
    if (node.voxels.size() < 6) continue;
    all += node.voxels.size();
    if (node.widest_gap > 2 * M_PI / 3) arcs += node.voxels.size();
  }
  return all ? double(arcs) / double(all) : 0.0;
}

//! A piece of skeleton all of whose nodes' balls lie within its widest one
//! (grown by a half; the widest sought along the bones, not only at nodes):
//! a ball or a stubby lump, not tubes. A limb's end reaches at least a
//! limb's radius beyond the body's ball.
bool is_a_blob(const Extraction& x, const ExtractedSkeleton& extracted) {
  const auto& nodes = extracted.skeleton.nodes;
  UnionFind pieces(nodes.size());
  for (auto [a, b] : extracted.skeleton.edges) pieces.join(size_t(a), size_t(b));
  auto find = [&](int v) { return pieces.find(size_t(v)); };
  std::map<size_t, std::pair<double, Eigen::Vector3d>> widest;  // per piece: radius and centre of its widest ball
  for (auto [a, b] : extracted.skeleton.edges)
    for (int k = 0; k <= 10; ++k) {
      Eigen::Vector3d p = nodes[size_t(a)] + (nodes[size_t(b)] - nodes[size_t(a)]) * (k / 10.0);
      double radius = x.inscribed_radius(p);
      auto [it, inserted] = widest.try_emplace(find(a), radius, p);
      if (radius > it->second.first) it->second = {radius, p};
    }
  for (const auto& [root, ball] : widest) {
    double reach = 0;
    for (size_t v = 0; v < nodes.size(); ++v)
      if (find(int(v)) == root) reach = std::max(reach, (nodes[v] - ball.second).norm() + extracted.radii[v]);
    if (reach <= 1.5 * ball.first) return true;
  }
  return false;
}

}  // namespace

ExtractedSkeleton extract_skeleton(const PointCloud& cloud, const std::string& source,
                                   const SkeletonExtractionOptions& options) {
  if (cloud.size() < kFewestPoints)
    throw InputError(source + ": " + std::to_string(cloud.size()) +
                     " points are too few to extract a skeleton from (at least " + std::to_string(kFewestPoints) + ")");
  ExtractedSkeleton result;
  size_t target = options.target_voxels ? options.target_voxels : std::min(kMostVoxels, cloud.size() / 4);
  // Fine enough for the target count, coarse enough that the sparsest part
  // of the scan stays one connected sheet.
  double voxel_size = std::max(voxel_size_for(cloud.points, target), kSpacingsPerVoxel * sparse_spacing(cloud.points));
  VoxelGraph voxels = build_voxel_graph(cloud.points, voxel_size);
  result.voxel_size = voxels.voxel_size;
  result.voxels = voxels.size();

  // Pieces smaller than a hundredth of the largest are outliers or specks.
  int component_count = 0;
  std::vector<int> component = voxel_components(voxels, component_count);
  std::vector<size_t> sizes(size_t(component_count), 0);
  for (int c : component) ++sizes[size_t(c)];
  size_t largest = *std::max_element(sizes.begin(), sizes.end());
  auto kept = [&](int c) { return sizes[size_t(c)] >= std::max<size_t>(20, largest / 100); };
  std::vector<uint32_t> seeds;
  std::vector<bool> seeded(size_t(component_count), false);
  std::vector<Eigen::Vector3d> surface_points;
  for (uint32_t v = 0; v < voxels.size(); ++v) {
    if (!kept(component[v])) {
      ++result.discarded_voxels;
      continue;
    }
    surface_points.push_back(voxels.centroids[v]);
    if (!seeded[size_t(component[v])]) {
      seeded[size_t(component[v])] = true;
      seeds.push_back(v);
      ++result.components;
    }
  }
  // The root of each piece: the far end of a double sweep, a limb's tip
  // where there are limbs (so that the bands cross every limb, not along it).
  std::vector<double> from_seed = geodesic_distances(voxels, seeds);
  std::vector<uint32_t> roots = seeds;
  std::vector<int> seed_index(size_t(component_count), -1);
  for (size_t s = 0; s < seeds.size(); ++s) seed_index[size_t(component[seeds[s]])] = int(s);
  for (uint32_t v = 0; v < voxels.size(); ++v) {
    int s = seed_index[size_t(component[v])];
    if (s >= 0 && from_seed[v] > from_seed[roots[size_t(s)]]) roots[size_t(s)] = v;
  }
  std::vector<double> distance = geodesic_distances(voxels, roots);
  for (uint32_t v = 0; v < voxels.size(); ++v)
    if (!kept(component[v])) distance[v] = -1;

  double band_width = options.band_voxels * voxels.voxel_size;
  LevelSetGraph levels = build_level_set_graph(voxels, distance, band_width);
  if (arc_fraction(levels) > 0.5)
    throw UnsupportedError(source +
                           ": the cloud is a sheet, not a body of tubes (most bands of distance along it are open "
                           "arcs): it has no curve skeleton; give a skeleton file");

  PointIndex<double> surface(surface_points);
  Extraction x{voxels, levels, surface, surface_points, band_width, WorkGraph(levels), {}};
  for (const auto& node : levels.nodes) x.position.push_back(node.centre);
  remove_false_cycles(x);
  prune_spurs(x);
  std::vector<Chain> chains = trace_chains(x);
  centre_on_cross_sections(x, chains);
  place_junctions(x, chains);
  for (const auto& chain : chains) bridge_arcs(x, chain.nodes, true);
  for (auto& chain : chains) {
    if (chain.closed()) continue;
    if (x.work.degree(chain.nodes.front()) == 1) place_end(x, chain.nodes);
    if (x.work.degree(chain.nodes.back()) == 1) {
      std::reverse(chain.nodes.begin(), chain.nodes.end());
      place_end(x, chain.nodes);
      std::reverse(chain.nodes.begin(), chain.nodes.end());
    }
  }

  // Emit: key nodes once, thinned chains between them.
  std::map<std::array<int, 2>, int> pair_count;
  for (const auto& chain : chains)
    ++pair_count[{std::min(chain.nodes.front(), chain.nodes.back()),
                  std::max(chain.nodes.front(), chain.nodes.back())}];
  std::map<int, int> output_index;
  auto emit = [&](int v) {
    auto [it, inserted] = output_index.try_emplace(v, int(result.skeleton.nodes.size()));
    if (inserted) result.skeleton.nodes.push_back(x.position[size_t(v)]);
    return it->second;
  };
  for (const auto& chain : chains) {
    int a = chain.nodes.front(), b = chain.nodes.back();
    size_t fewest = chain.closed() ? 2 : pair_count[{std::min(a, b), std::max(a, b)}] > 1 ? 1 : 0;
    std::vector<int> thinned = thin_chain(x, chain.nodes, fewest);
    if (thinned.size() < 2 || (thinned.size() == 2 && (x.position[size_t(a)] - x.position[size_t(b)]).norm() == 0))
      continue;
    for (size_t k = 1; k < thinned.size(); ++k) {
      // Inner nodes are fresh per chain; key nodes are shared.
      int from = k == 1 ? emit(thinned[0]) : int(result.skeleton.nodes.size()) - 1;
      int to;
      if (k + 1 == thinned.size()) {
        to = emit(thinned[k]);
      } else {
        to = int(result.skeleton.nodes.size());
        result.skeleton.nodes.push_back(x.position[size_t(thinned[k])]);
      }
      if (from != to) result.skeleton.edges.push_back({from, to});
    }
  }
  for (const auto& p : result.skeleton.nodes) result.radii.push_back(x.inscribed_radius(p));
  if (result.skeleton.edges.empty() || is_a_blob(x, result))
    throw UnsupportedError(source +
                           ": the cloud is a single blob with no limbs (no part of it reaches out of its widest "
                           "inscribed ball): it has no curve skeleton; give a skeleton file");
  return result;
}

}  // namespace mcquad
