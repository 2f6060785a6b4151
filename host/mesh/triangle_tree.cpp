#include "mesh/triangle_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace mcquad {

namespace {

//! The bits of a 10-bit integer spread to every third bit.
uint32_t spread_bits(uint32_t x) {
  x = (x | (x << 16)) & 0x030000FFu;
  x = (x | (x << 8)) & 0x0300F00Fu;
  x = (x | (x << 4)) & 0x030C30C3u;
  x = (x | (x << 2)) & 0x09249249u;
  return x;
}

}  // namespace

TriangleTree::TriangleTree(const MeshTriangles& triangles) : triangles_(triangles) {
  const size_t n = triangles.size();
  boxes_.resize(n);
  Box all;
  std::vector<Eigen::Vector3f> centroids(n);
  for (size_t t = 0; t < n; ++t) {
    boxes_[t] = box_of(t);
    centroids[t] = triangles.centroid(t).cast<float>();
    all.extend(centroids[t]);
  }
  if (n == 0) return;
  // Sorted as plain integers, code above index: the same order as by code,
  // ties by index, at a fraction of an indirect comparison's cost.
  std::vector<uint64_t> keys(n);
  const Eigen::Array3f scale = 1023.0f / all.sizes().array().max(1e-30f);
  for (size_t t = 0; t < n; ++t) {
    Eigen::Array3f cell = ((centroids[t] - all.min()).array() * scale).min(1023.0f).max(0.0f);
    uint64_t code =
        spread_bits(uint32_t(cell.x())) << 2 | spread_bits(uint32_t(cell.y())) << 1 | spread_bits(uint32_t(cell.z()));
    keys[t] = code << 32 | t;
  }
  std::sort(keys.begin(), keys.end());
  order_.resize(n);
  for (size_t k = 0; k < n; ++k) order_[k] = int(keys[k] & 0xffffffffu);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  nodes_.emplace_back();
  build(0, 0, int(n));
  fit_boxes();
}

TriangleTree::Box TriangleTree::box_of(size_t t) const {
  const MeshTriangles& triangles = triangles_;
  Eigen::Vector3d lo = triangles.corner(t, 0).cwiseMin(triangles.corner(t, 1)).cwiseMin(triangles.corner(t, 2));
  Eigen::Vector3d hi = triangles.corner(t, 0).cwiseMax(triangles.corner(t, 1)).cwiseMax(triangles.corner(t, 2));
  Eigen::Vector3f low, high;
  for (int k = 0; k < 3; ++k) {
    low[k] = std::nextafter(float(lo[k]), -INFINITY);
    high[k] = std::nextafter(float(hi[k]), INFINITY);
  }
  return {low, high};
}

void TriangleTree::refit(const std::vector<char>& moved) {
  if (parent_.empty()) index_parents();
  for (size_t t = 0; t < boxes_.size(); ++t) {
    if (!moved[t]) continue;
    boxes_[t] = box_of(t);
    // Its leaf and the nodes above, up to the first whose box stays (the
    // boxes above it are then as they were): a few nodes a triangle, where
    // every node's box cost a pass over the whole tree at each refresh.
    for (int node = leaf_of_[t]; node >= 0; node = parent_[size_t(node)]) {
      const Box box = box_from_below(nodes_[size_t(node)]);
      Box& kept = nodes_[size_t(node)].box;
      if (box.min() == kept.min() && box.max() == kept.max()) break;
      kept = box;
    }
  }
}

void TriangleTree::index_parents() {
  parent_.assign(nodes_.size(), -1);
  leaf_of_.assign(boxes_.size(), -1);
  for (size_t k = 0; k < nodes_.size(); ++k) {
    const Node& node = nodes_[k];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) leaf_of_[size_t(order_[size_t(i)])] = int(k);
    } else {
      parent_[size_t(node.first)] = parent_[size_t(node.first + 1)] = int(k);
    }
  }
}

TriangleTree::Box TriangleTree::box_from_below(const Node& node) const {
  if (node.count == 0) return nodes_[size_t(node.first)].box.merged(nodes_[size_t(node.first + 1)].box);
  Box box;
  for (int i = node.first; i < node.first + node.count; ++i) box.extend(boxes_[size_t(order_[size_t(i)])]);
  return box;
}

void TriangleTree::fit_boxes() {
  // Children come after their parent, so one backward sweep sees them first.
  for (size_t k = nodes_.size(); k-- > 0;) nodes_[k].box = box_from_below(nodes_[k]);
}

void TriangleTree::build(int node, int begin, int end) {
  if (end - begin <= kLeafSize) {
    nodes_[size_t(node)].first = begin;
    nodes_[size_t(node)].count = end - begin;
    return;
  }
  int children = int(nodes_.size());
  nodes_[size_t(node)].first = children;
  nodes_[size_t(node)].count = 0;
  nodes_.emplace_back();
  nodes_.emplace_back();
  int middle = begin + (end - begin) / 2;
  build(children, begin, middle);
  build(children + 1, middle, end);
}

std::vector<char> TriangleTree::wanted_nodes(const std::vector<char>* wanted) const {
  std::vector<char> has(nodes_.size(), wanted ? 0 : 1);
  if (!wanted) return has;
  // Children come after their parent, so one backward sweep sees them first.
  for (size_t k = nodes_.size(); k-- > 0;) {
    const Node& node = nodes_[k];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) has[k] |= (*wanted)[size_t(order_[size_t(i)])] != 0;
    } else {
      has[k] = has[size_t(node.first)] | has[size_t(node.first + 1)];
    }
  }
  return has;
}

std::vector<std::pair<int, int>> TriangleTree::split_pairs(const std::vector<char>& has_wanted, size_t count,
                                                           float gap) const {
  // Breadth first: a pair splits into the pairs of its children, as the
  // traversal would, until there are enough or only leaves are left.
  std::vector<std::pair<int, int>> pairs{{0, 0}}, next;
  for (bool split = true; split && pairs.size() < count;) {
    split = false;
    next.clear();
    for (auto [a, b] : pairs) {
      const Node& na = nodes_[size_t(a)];
      const Node& nb = nodes_[size_t(b)];
      if ((!has_wanted[size_t(a)] && !has_wanted[size_t(b)]) || (a != b && !within_gap(na.box, nb.box, gap))) continue;
      if (a == b && na.count == 0) {
        next.insert(next.end(), {{na.first, na.first}, {na.first + 1, na.first + 1}, {na.first, na.first + 1}});
        split = true;
      } else if (a != b && na.count == 0) {
        next.insert(next.end(), {{na.first, b}, {na.first + 1, b}});
        split = true;
      } else if (a != b && nb.count == 0) {
        next.insert(next.end(), {{a, nb.first}, {a, nb.first + 1}});
        split = true;
      } else {
        next.emplace_back(a, b);
      }
    }
    pairs.swap(next);
  }
  return pairs;
}

std::pair<double, long> TriangleTree::nearest(const Eigen::Vector3d& p, long hint) const {
  double best = INFINITY;
  long best_triangle = -1;
  if (nodes_.empty()) return {best, best_triangle};
  if (hint >= 0 && size_t(hint) < size()) {
    best = triangle_distance(p, size_t(hint));
    best_triangle = hint;
  }
  const Eigen::Vector3f q = p.cast<float>();
  const double slack = rounding_slack(q);
  const auto box_distance = [&](const Box& box) { return box_distance2(box, q); };
  const auto beyond_best = [&](double scaled_d2) { return beyond(scaled_d2, best, slack); };
  std::pair<double, int> stack[128];
  int top = 0;
  stack[top++] = {0.0, 0};
  while (top > 0) {
    auto [distance, index] = stack[--top];
    if (beyond_best(distance)) continue;
    const Node& node = nodes_[size_t(index)];
    if (node.count > 0) {
      for (int k = node.first; k < node.first + node.count; ++k) {
        size_t t = size_t(order_[size_t(k)]);
        if (beyond_best(box_distance(boxes_[t]))) continue;  // a float test spares most exact ones
        double d = triangle_distance(p, t);
        if (nearer(d, long(t), best, best_triangle)) best = d, best_triangle = long(t);
      }
      continue;
    }
    // The nearer child last, so it is taken first.
    double d0 = box_distance(nodes_[size_t(node.first)].box), d1 = box_distance(nodes_[size_t(node.first + 1)].box);
    if (d0 < d1) {
      stack[top++] = {d1, node.first + 1};
      stack[top++] = {d0, node.first};
    } else {
      stack[top++] = {d0, node.first};
      stack[top++] = {d1, node.first + 1};
    }
  }
  return {best, best_triangle};
}

}  // namespace mcquad
