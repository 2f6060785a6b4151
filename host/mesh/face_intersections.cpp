#include "mesh/face_intersections.h"

#include "core/shared_math.h"
#include "mesh/triangle_tree.h"

#include <omp.h>

#include <algorithm>

namespace mcquad {
bool triangles_intersect(const Eigen::Vector3d* a, const Eigen::Vector3d* b) {
  // The guard's test, shared with the device (kernels/shared/mcq_guard.h).
  const device::mcq_d3 pa[3] = {to_device(a[0]), to_device(a[1]), to_device(a[2])};
  const device::mcq_d3 pb[3] = {to_device(b[0]), to_device(b[1]), to_device(b[2])};
  return device::mcq_guard_triangles_intersect(pa, pb) != 0;
}

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  // By Voronoi regions (Ericson, Real-Time Collision Detection 5.1.5).
  Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  Eigen::Vector3d bp = p - b;
  double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  Eigen::Vector3d cp = p - c;
  double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  double denom = 1.0 / (va + vb + vc);
  return a + ab * vb * denom + ac * vc * denom;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  return (p - closest_point_on_triangle(p, a, b, c)).norm();
}

MeshTriangles triangulate(const QuadMesh& mesh) {
  MeshTriangles triangles;
  triangles.positions.reserve(mesh.n_vertices());
  for (auto v : mesh.vertices()) triangles.positions.push_back(point_of(mesh, v));
  triangles.corners.reserve(2 * mesh.n_faces());
  triangles.face.reserve(2 * mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::vector<int> ids;
    for (auto v : mesh.fv_range(f)) ids.push_back(v.idx());
    for (size_t k = 1; k + 1 < ids.size(); ++k) {
      triangles.corners.push_back({ids[0], ids[k], ids[k + 1]});
      triangles.face.push_back(f.idx());
    }
  }
  return triangles;
}

MeshTriangles triangulate(const std::vector<uint32_t>& quads, const std::vector<float>& positions) {
  MeshTriangles triangles;
  triangles.positions.reserve(positions.size() / 3);
  for (size_t i = 0; i + 2 < positions.size(); i += 3)
    triangles.positions.emplace_back(positions[i], positions[i + 1], positions[i + 2]);
  size_t faces = quads.size() / 4;
  triangles.corners.reserve(2 * faces);
  triangles.face.reserve(2 * faces);
  for (size_t f = 0; f < faces; ++f) {
    const uint32_t* q = &quads[4 * f];
    triangles.corners.push_back({int(q[0]), int(q[1]), int(q[2])});
    triangles.corners.push_back({int(q[0]), int(q[2]), int(q[3])});
    triangles.face.insert(triangles.face.end(), {int(f), int(f)});
  }
  return triangles;
}

bool triangles_share_a_vertex(const MeshTriangles& triangles, size_t a, size_t b) {
  for (int i : triangles.corners[a])
    for (int j : triangles.corners[b])
      if (i == j) return true;
  return false;
}

bool triangle_pair_intersects(const MeshTriangles& triangles, size_t a, size_t b) {
  if (triangles_share_a_vertex(triangles, a, b)) return false;
  Eigen::Vector3d pa[3], pb[3];
  for (int k = 0; k < 3; ++k) pa[k] = triangles.corner(a, k), pb[k] = triangles.corner(b, k);
  Eigen::Vector3d lo_a = pa[0].cwiseMin(pa[1]).cwiseMin(pa[2]), hi_a = pa[0].cwiseMax(pa[1]).cwiseMax(pa[2]);
  Eigen::Vector3d lo_b = pb[0].cwiseMin(pb[1]).cwiseMin(pb[2]), hi_b = pb[0].cwiseMax(pb[1]).cwiseMax(pb[2]);
  if ((lo_a.array() > hi_b.array()).any() || (lo_b.array() > hi_a.array()).any()) return false;
  return triangles_intersect(pa, pb);
}

std::vector<std::pair<int, int>> intersecting_face_pairs(const QuadMesh& mesh) {
  return intersecting_face_pairs(triangulate(mesh));
}

std::vector<std::pair<int, int>> intersecting_face_pairs(const MeshTriangles& triangles,
                                                         const std::vector<char>* only_faces) {
  const size_t n = triangles.size();
  if (n == 0) return {};
  // The candidates are the triangles whose boxes overlap (mesh/triangle_tree.h,
  // the tree the cloud → mesh distances use too), then an exact test.
  TriangleTree tree(triangles);
  std::vector<char> wanted_triangles;
  if (only_faces) {
    wanted_triangles.resize(n);
    for (size_t t = 0; t < n; ++t) wanted_triangles[t] = (*only_faces)[size_t(triangles.face[t])];
  }
  // Threads pay off only on large meshes (intersecting_face_pairs runs on
  // every mesh `mcquad metrics` measures, often small ones).
  FacePairsFound found;
  tree.for_each_overlapping_pair(only_faces ? &wanted_triangles : nullptr, [&](size_t a, size_t b, int thread) {
    if (triangles.face[a] != triangles.face[b] && triangle_pair_intersects(triangles, a, b))
      found.add(triangles, a, b, thread);
  });
  return found.sorted();
}

FacePairsFound::FacePairsFound() : per_thread_(static_cast<size_t>(omp_get_max_threads())) {}

void FacePairsFound::add(const MeshTriangles& triangles, size_t a, size_t b, int thread) {
  const int fa = triangles.face[a], fb = triangles.face[b];
  per_thread_[size_t(thread)].emplace_back(std::min(fa, fb), std::max(fa, fb));
}

std::vector<std::pair<int, int>> FacePairsFound::sorted() const {
  std::vector<std::pair<int, int>> pairs;
  for (const auto& some : per_thread_) pairs.insert(pairs.end(), some.begin(), some.end());
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace mcquad
