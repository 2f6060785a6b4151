#include "skeleton/skeleton_graph.h"

#include <algorithm>
#include <numeric>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/progress.h"

namespace mcquad {
namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) { return parent[i] == i ? i : parent[i] = find(parent[i]); }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

std::string describe_node(const SkeletonData& data, int node) {
  std::ostringstream s;
  const auto& p = data.nodes[node];
  s << "node " << node + 1 << " (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

//! Groups nodes closer than `tolerance` (sweep over x-sorted nodes).
UnionFind merge_coincident(const SkeletonData& data, double tolerance) {
  UnionFind groups(data.nodes.size());
  std::vector<int> order(data.nodes.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return data.nodes[a].x() < data.nodes[b].x(); });
  for (size_t i = 0; i < order.size(); ++i) {
    for (size_t j = i + 1; j < order.size() && data.nodes[order[j]].x() - data.nodes[order[i]].x() <= tolerance; ++j) {
      if ((data.nodes[order[j]] - data.nodes[order[i]]).norm() <= tolerance) groups.unite(order[i], order[j]);
    }
  }
  return groups;
}

}  // namespace

NodeKind SkeletonGraph::kind(int node) const {
  int d = degree(node);
  return d == 1 ? NodeKind::kEnd : d == 2 ? NodeKind::kRegular : NodeKind::kJunction;
}

int SkeletonGraph::independent_cycles(int component_index) const {
  int vertices = 0, edge_count = 0;
  for (size_t v = 0; v < node_count(); ++v) vertices += component[v] == component_index;
  for (const auto& e : edges) edge_count += component[e[0]] == component_index;
  return edge_count - vertices + 1;
}

std::vector<std::vector<int>> SkeletonGraph::node_bones() const {
  std::vector<std::vector<int>> bones(node_count());
  for (size_t b = 0; b < edges.size(); ++b)
    for (int end : edges[b]) bones[size_t(end)].push_back(int(b));
  return bones;
}

std::vector<int> SkeletonGraph::chain_from(int start, int next) const {
  std::vector<int> chain{start, next};
  while (kind(chain.back()) == NodeKind::kRegular && chain.back() != start) {
    int current = chain.back(), previous = chain[chain.size() - 2];
    int a = neighbours[size_t(current)][0], b = neighbours[size_t(current)][1];
    chain.push_back(a == previous ? b : a);
  }
  return chain;
}

std::vector<Branch> SkeletonGraph::branches() const {
  std::vector<Branch> result;
  std::set<std::pair<int, int>> used;
  auto key = [](int a, int b) { return std::make_pair(std::min(a, b), std::max(a, b)); };
  auto walk = [&](int start, int next, Branch& branch) {
    int previous = start;
    int current = next;
    branch.nodes = {start};
    used.insert(key(start, next));
    while (kind(current) == NodeKind::kRegular && current != start) {
      branch.nodes.push_back(current);
      int a = neighbours[current][0], b = neighbours[current][1];
      int following = a == previous ? b : a;
      used.insert(key(current, following));
      previous = current;
      current = following;
    }
    branch.nodes.push_back(current);
  };
  for (size_t node = 0; node < node_count(); ++node) {
    if (kind(int(node)) == NodeKind::kRegular) continue;
    for (int next : neighbours[node]) {
      if (used.count(key(int(node), next))) continue;
      Branch branch;
      walk(int(node), next, branch);
      result.push_back(std::move(branch));
    }
  }
  // What is left are pure loops: components whose nodes are all regular.
  for (size_t node = 0; node < node_count(); ++node) {
    if (kind(int(node)) != NodeKind::kRegular || used.count(key(int(node), neighbours[node][0]))) continue;
    Branch loop;
    walk(int(node), neighbours[node][0], loop);
    loop.nodes.pop_back();  // the walk returned to its start
    loop.closed = true;
    result.push_back(std::move(loop));
  }
  return result;
}

SkeletonGraph build_skeleton_graph(const SkeletonData& data, const std::string& source, double merge_tolerance) {
  if (data.nodes.empty() || data.edges.empty()) throw InputError(source + ": the skeleton has no bones");
  // The readers guarantee these; skeletons made in memory may not.
  for (size_t i = 0; i < data.nodes.size(); ++i)
    if (!data.nodes[i].allFinite())
      throw InputError(source + ": node " + std::to_string(i + 1) + " has a NaN or infinite coordinate");
  for (size_t i = 0; i < data.edges.size(); ++i)
    for (int end : data.edges[i])
      if (end < 0 || size_t(end) >= data.nodes.size())
        throw InputError(source + ": bone " + std::to_string(i + 1) + " names node " + std::to_string(end + 1) +
                         " of " + std::to_string(data.nodes.size()));
  Eigen::Vector3d lo = data.nodes[0], hi = data.nodes[0];
  for (const auto& p : data.nodes) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  if (merge_tolerance < 0) merge_tolerance = 1e-6 * std::max((hi - lo).norm(), 1e-30);
  UnionFind groups = merge_coincident(data, merge_tolerance);

  std::vector<int> new_index(data.nodes.size(), -1);
  SkeletonGraph graph;
  size_t merged = 0;
  for (size_t i = 0; i < data.nodes.size(); ++i) {
    int root = groups.find(int(i));
    if (new_index[root] < 0) {
      new_index[root] = int(graph.positions.size());
      graph.positions.push_back(data.nodes[root]);
    } else if (root != int(i)) {
      ++merged;
    }
    new_index[i] = new_index[root];
  }
  if (merged > 0) warn(source + ": merged " + std::to_string(merged) + " coincident skeleton node(s)");

  std::set<std::pair<int, int>> seen;
  size_t duplicates = 0;
  std::vector<bool> touched(graph.positions.size(), false);
  for (const auto& e : data.edges) {
    int a = new_index[e[0]], b = new_index[e[1]];
    if (a == b)
      throw InputError(source + ": bone " + std::to_string(e[0] + 1) + "-" + std::to_string(e[1] + 1) + " at " +
                       describe_node(data, e[0]) + " is a self-loop (its ends coincide)");
    touched[a] = touched[b] = true;
    if (!seen.insert({std::min(a, b), std::max(a, b)}).second) {
      ++duplicates;
      continue;
    }
    graph.edges.push_back({a, b});
  }
  if (duplicates > 0) warn(source + ": merged " + std::to_string(duplicates) + " duplicate bone(s)");
  for (size_t i = 0; i < data.nodes.size(); ++i) {
    if (!touched[new_index[i]])
      throw InputError(source + ": " + describe_node(data, int(i)) + " is isolated (no bone uses it)");
  }

  graph.neighbours.assign(graph.positions.size(), {});
  UnionFind components(graph.positions.size());
  for (const auto& e : graph.edges) {
    graph.neighbours[e[0]].push_back(e[1]);
    graph.neighbours[e[1]].push_back(e[0]);
    components.unite(e[0], e[1]);
  }
  graph.component.assign(graph.positions.size(), -1);
  std::vector<int> component_id(graph.positions.size(), -1);
  for (size_t v = 0; v < graph.positions.size(); ++v) {
    int root = components.find(int(v));
    if (component_id[root] < 0) component_id[root] = graph.component_count++;
    graph.component[v] = component_id[root];
  }
  return graph;
}

}  // namespace mcquad
