#pragma once

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "io/skeleton_io.h"

namespace mcquad {

enum class NodeKind { kEnd, kRegular, kJunction };

//! A chain of skeleton nodes between two non-regular nodes (an end or a
//! junction), or a pure loop of regular nodes (closed, first node not repeated).
struct Branch {
  std::vector<int> nodes;
  bool closed = false;
};

//! The skeleton as a graph: coincident nodes merged, duplicate bones merged,
//! nodes classified by degree, split into branches and components.
struct SkeletonGraph {
  std::vector<Eigen::Vector3d> positions;
  std::vector<std::array<int, 2>> edges;
  std::vector<std::vector<int>> neighbours;
  std::vector<int> component;  //!< component index per node
  int component_count = 0;

  size_t node_count() const { return positions.size(); }
  int degree(int node) const { return int(neighbours[node].size()); }
  NodeKind kind(int node) const;
  //! Independent cycles (first Betti number) of one component: E - V + 1.
  int independent_cycles(int component_index) const;
  //! Branches: chains between non-regular nodes, and pure loops.
  std::vector<Branch> branches() const;
  //! The chain of nodes from non-regular node `start` through its neighbour
  //! `next` to the next non-regular node, or back to `start` (both inclusive).
  std::vector<int> chain_from(int start, int next) const;
  //! Per node, the bones (indices into edges) that end there.
  std::vector<std::vector<int>> node_bones() const;
};

//! Builds the graph from a skeleton as read. `source` (the file name) prefixes
//! every message. Nodes closer than `merge_tolerance` (default: 1e-6 of the
//! bounding box diagonal) are merged and duplicate bones dropped, each with a
//! warning; a bone from a node to itself and a node with no bone are
//! InputErrors naming the node.
SkeletonGraph build_skeleton_graph(const SkeletonData& data, const std::string& source, double merge_tolerance = -1.0);

}  // namespace mcquad
