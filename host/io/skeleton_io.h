#pragma once

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace mcquad {

//! A skeleton as read from a file: nodes and undirected edges (bones),
//! before any merging or classification (see skeleton/skeleton_graph.h).
struct SkeletonData {
  std::vector<Eigen::Vector3d> nodes;
  std::vector<std::array<int, 2>> edges;
};

//! Reads a skeleton by extension: .obj (v lines, and l lines listing a
//! polyline of 1-based or negative relative indices) or .cgal/.polylines/.txt
//! (CGAL's polylines: "n x1 y1 z1 ... xn yn zn" per line; equal coordinates
//! are merged later by the skeleton graph). InputError naming file and line.
SkeletonData read_skeleton(const std::string& path);

//! Writes a skeleton as OBJ (v and l lines), atomically.
void write_skeleton_obj(const std::string& path, const SkeletonData& skeleton);

}  // namespace mcquad
