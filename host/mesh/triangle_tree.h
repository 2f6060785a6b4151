#pragma once

#include <omp.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/face_intersections.h"

namespace mcquad {

//! A bounding-volume hierarchy over a mesh's triangles: the exact nearest
//! triangle to a point (cloud → mesh distances) and the triangles whose
//! boxes overlap a box (the self-intersection broad phase), from one tree.
//! Built as a linear BVH: triangles sorted by their centroids' Morton codes,
//! ranges halved down to kLeafSize triangles a leaf, boxes fitted bottom up
//! (O(n log n) in one sort; a median split per level cost four times more
//! on the knot's mesh). Boxes are in floats rounded outward (half
//! the memory at millions of triangles; the exact tests are in doubles).
class TriangleTree {
 public:
  static constexpr int kLeafSize = 4;
  using Box = Eigen::AlignedBox3f;

  //! `triangles` must outlive the tree.
  explicit TriangleTree(const MeshTriangles& triangles);

  //! The nearest triangle to `p` and the distance to it (exact: every
  //! triangle whose box is nearer than the best found so far is tested).
  //! An empty tree answers (infinity, -1). Of equally near triangles the
  //! lowest index. `hint`, a triangle likely to be near (the previous
  //! query's answer, for queries in spatial order), only makes the search
  //! faster: the answer is the same.
  std::pair<double, long> nearest(const Eigen::Vector3d& p, long hint = -1) const;

  //! Calls `visit(t)` for every triangle t whose box comes within `gap` of
  //! `box` (per axis; the pair test of for_each_overlapping_pair); with gap
  //! 0, whose box overlaps it.
  template <typename Visit>
  void for_each_within_gap(const Box& box, float gap, Visit&& visit) const {
    if (nodes_.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[size_t(stack[--top])];
      if (!within_gap(node.box, box, gap)) continue;
      if (node.count > 0) {
        for (int k = node.first; k < node.first + node.count; ++k)
          if (within_gap(boxes_[size_t(order_[size_t(k)])], box, gap)) visit(size_t(order_[size_t(k)]));
      } else {
        stack[top++] = node.first;
        stack[top++] = node.first + 1;
      }
    }
  }

  //! Takes the positions the triangles hold now: the boxes of the `moved`
  //! triangles (per triangle, nonzero) are made again, and the boxes of
  //! the nodes above them. The tree's order stays as it was built, so
  //! it answers as before, exactly, and as fast while the triangles have
  //! moved little against their spacing (CloseTrianglePairs: a few
  //! triangles at a time, where a new tree cost a sort of all of them).
  void refit(const std::vector<char>& moved);

  //! Calls `visit(a, b)` once for every unordered pair of distinct triangles
  //! whose boxes overlap, or come within `gap`, and of which at least one
  //! is `wanted` (per triangle, nonzero; null: all). One traversal of the
  //! tree against itself; on more than `parallel_above` triangles the
  //! threads share it, `visit` then being called from several at once with
  //! its thread's number (0 to omp_get_max_threads() - 1) as the third
  //! argument.
  template <typename Visit>
  void for_each_overlapping_pair(const std::vector<char>* wanted, Visit&& visit, size_t parallel_above = 8192,
                                 float gap = 0.0f) const;

  const Box& box(size_t triangle) const { return boxes_[triangle]; }
  size_t size() const { return boxes_.size(); }

  //! The exact distance from `p` to a triangle.
  double triangle_distance(const Eigen::Vector3d& p, size_t triangle) const {
    return point_triangle_distance(p, triangles_.corner(triangle, 0), triangles_.corner(triangle, 1),
                                   triangles_.corner(triangle, 2));
  }
  //! Boxes are floats rounded outward, but a query q is rounded too: a
  //! box's distance may come out a float's rounding over the truth. So a
  //! box counts as beyond `best` (exact) when sqrt(d2) (1 - 1e-6) - slack
  //! > best, with slack = 1e-6 |q|, compared squared (no square root per
  //! box); box_distance2 gives d2 (1 - 1e-6)^2.
  static double box_distance2(const Box& box, const Eigen::Vector3f& q) {
    return double(box.squaredExteriorDistance(q)) * ((1 - 1e-6) * (1 - 1e-6));
  }
  static double rounding_slack(const Eigen::Vector3f& q) { return 1e-6 * double(q.norm()); }
  static bool beyond(double box_d2, double best, double slack) { return box_d2 > (best + slack) * (best + slack); }
  //! Whether triangle t at distance d is a better answer than best_triangle
  //! at `best`: nearer, or as near with a lower index. A point beyond a
  //! vertex is exactly as near every triangle around it; without the index
  //! the one met first (by way of the hint) would win, and a caller's result
  //! would follow how its queries were split among threads.
  static bool nearer(double d, long t, double best, long best_triangle) {
    return d < best || (d == best && t < best_triangle);
  }

 private:
  //! A leaf holds order_[first, first + count); an inner node (count 0) has
  //! its children at nodes_[first] and nodes_[first + 1].
  struct Node {
    Box box;
    int first = 0, count = 0;
  };
  //! Triangle t's box at the positions it holds, in floats rounded outward.
  Box box_of(size_t t) const;
  void build(int node, int begin, int end);
  //! A node's box from its triangles' or its children's.
  Box box_from_below(const Node& node) const;
  //! Every node's box from its triangles' or children's.
  void fit_boxes();
  //! Fills parent_ and leaf_of_ (refit's way up).
  void index_parents();
  //! Per node: does its subtree hold a wanted triangle?
  std::vector<char> wanted_nodes(const std::vector<char>* wanted) const;
  //! Node pairs (i <= j) whose overlapping triangle pairs together are all
  //! of them: at least `count` pairs where the tree is deep enough.
  std::vector<std::pair<int, int>> split_pairs(const std::vector<char>& has_wanted, size_t count, float gap) const;
  template <typename Visit>
  void visit_pairs_below(int i, int j, const std::vector<char>* wanted, const std::vector<char>& has_wanted, float gap,
                         Visit&& visit, int thread) const;
  //! Whether two boxes overlap or come within `gap` (per axis).
  static bool within_gap(const Box& a, const Box& b, float gap) {
    return (a.min().array() <= b.max().array() + gap).all() && (b.min().array() <= a.max().array() + gap).all();
  }

  const MeshTriangles& triangles_;
  std::vector<Box> boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  //! Per node its parent (-1 at the root), per triangle its leaf: made at
  //! the first refit, for trees that are refitted.
  std::vector<int> parent_, leaf_of_;
};

template <typename Visit>
void TriangleTree::visit_pairs_below(int i, int j, const std::vector<char>* wanted, const std::vector<char>& has_wanted,
                                     float gap, Visit&& visit, int thread) const {
  std::pair<int, int> stack[256];
  int top = 0;
  stack[top++] = {i, j};
  auto is_wanted = [&](int t) { return !wanted || (*wanted)[size_t(t)]; };
  while (top > 0) {
    auto [a, b] = stack[--top];
    if (!has_wanted[size_t(a)] && !has_wanted[size_t(b)]) continue;
    const Node& na = nodes_[size_t(a)];
    const Node& nb = nodes_[size_t(b)];
    if (a != b && !within_gap(na.box, nb.box, gap)) continue;
    if (na.count > 0 && nb.count > 0) {
      for (int x = na.first; x < na.first + na.count; ++x)
        for (int y = (a == b ? x + 1 : nb.first); y < nb.first + nb.count; ++y) {
          int s = order_[size_t(x)], t = order_[size_t(y)];
          if ((is_wanted(s) || is_wanted(t)) && within_gap(boxes_[size_t(s)], boxes_[size_t(t)], gap))
            visit(size_t(std::min(s, t)), size_t(std::max(s, t)), thread);
        }
      continue;
    }
    if (a == b) {
      stack[top++] = {na.first, na.first};
      stack[top++] = {na.first + 1, na.first + 1};
      stack[top++] = {na.first, na.first + 1};
    } else if (nb.count > 0 || (na.count == 0 && na.box.volume() >= nb.box.volume())) {
      stack[top++] = {na.first, b};
      stack[top++] = {na.first + 1, b};
    } else {
      stack[top++] = {a, nb.first};
      stack[top++] = {a, nb.first + 1};
    }
  }
}

template <typename Visit>
void TriangleTree::for_each_overlapping_pair(const std::vector<char>* wanted, Visit&& visit, size_t parallel_above,
                                             float gap) const {
  if (nodes_.empty()) return;
  std::vector<char> has_wanted = wanted_nodes(wanted);
  if (size() <= parallel_above) {
    visit_pairs_below(0, 0, wanted, has_wanted, gap, visit, 0);
    return;
  }
  std::vector<std::pair<int, int>> tasks = split_pairs(has_wanted, 256, gap);
#pragma omp parallel for schedule(dynamic, 1)
  for (long k = 0; k < long(tasks.size()); ++k)
    visit_pairs_below(tasks[size_t(k)].first, tasks[size_t(k)].second, wanted, has_wanted, gap, visit,
                      omp_get_thread_num());
}

}  // namespace mcquad
