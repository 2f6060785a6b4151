#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "core/quad_mesh.h"
#include "generate/shapes.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad::test {

//! A fresh directory under the system temp dir, removed at the end.
class TempDir {
 public:
  TempDir() {
    path_ = std::filesystem::temp_directory_path() /
            ("mcquad-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter()++));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(file(name), std::ios::binary) << text;
    return file(name);
  }

 private:
  static int& counter() {
    static int c = 0;
    return c;
  }
  std::filesystem::path path_;
};

//! OpenCL tests may skip only outside CI: with CI=true or
//! MCQUAD_REQUIRE_OPENCL=1 a missing device is a failure.
//! Appends an n x n grid of quads to `mesh`, vertex (i, j) at place(i, j).
template <typename Place>
void add_quad_grid(QuadMesh& mesh, int n, Place&& place) {
  std::vector<QuadMesh::VertexHandle> v;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) v.push_back(mesh.add_vertex(place(i, j)));
  auto at = [&](int a, int b) { return v[size_t(a * (n + 1) + b)]; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) mesh.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
}

//! A grid of quads over [0, n]^2 whose vertices are jittered in height,
//! plus a second, tilted grid through it: many crossings, many near misses.
inline QuadMesh crumpled_sheets(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  QuadMesh mesh;
  for (int sheet = 0; sheet < 2; ++sheet)
    add_quad_grid(mesh, n, [&](int i, int j) {
      double x = i, y = j, z = jitter(random);
      if (sheet == 1) z += 0.2 * (x - n / 2.0);  // tilted through the first sheet
      return QuadMesh::Point(x + 0.37 * sheet, y + 0.21 * sheet, z);
    });
  return mesh;
}

//! The cube [0, 1]^3 as six outward quads; `inward` turns every face over.
inline QuadMesh unit_cube(bool inward = false) {
  QuadMesh mesh;
  std::vector<QuadMesh::VertexHandle> v;
  for (int k = 0; k < 8; ++k) v.push_back(mesh.add_vertex(QuadMesh::Point(k & 1, (k >> 1) & 1, (k >> 2) & 1)));
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    if (inward)
      mesh.add_face(v[size_t(f[3])], v[size_t(f[2])], v[size_t(f[1])], v[size_t(f[0])]);
    else
      mesh.add_face(v[size_t(f[0])], v[size_t(f[1])], v[size_t(f[2])], v[size_t(f[3])]);
  }
  return mesh;
}

inline bool opencl_required() {
  const char* ci = std::getenv("CI");
  const char* require = std::getenv("MCQUAD_REQUIRE_OPENCL");
  return (ci && std::string(ci) == "true") || (require && std::string(require) == "1");
}

inline GeneratedShape small_shape(const std::string& name, size_t points, ShapeOptions options = {}) {
  options.points = points;
  return generate_shape(name, options);
}

//! A generated shape with its skeleton's graph and the cloud's bones and
//! radii: what the skeleton and initial-mesh tests start from (`name` is
//! also the source their messages name).
struct ShapeWithBones {
  GeneratedShape shape;
  SkeletonGraph graph;
  BoneAssignment bones;
  ShapeWithBones(const std::string& name, size_t points, const ShapeOptions& options = {})
      : shape(small_shape(name, points, options)),
        graph(build_skeleton_graph(shape.skeleton, name)),
        bones(assign_points_to_bones(graph, shape.cloud, name)) {}
};

}  // namespace mcquad::test
