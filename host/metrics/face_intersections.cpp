#include "metrics/face_intersections.h"

#include <algorithm>
#include <set>
#include <unordered_map>

namespace mcquad {
namespace {

bool segment_hits_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d* t) {
  // Moller-Trumbore on the segment p + s (q - p), s in [0, 1].
  const double eps = 1e-12;
  Eigen::Vector3d d = q - p, e1 = t[1] - t[0], e2 = t[2] - t[0];
  Eigen::Vector3d h = d.cross(e2);
  double det = e1.dot(h);
  if (std::abs(det) < eps * e1.norm() * e2.norm() * d.norm()) return false;
  double inv = 1.0 / det;
  Eigen::Vector3d s = p - t[0];
  double u = inv * s.dot(h);
  if (u < 0 || u > 1) return false;
  Eigen::Vector3d qv = s.cross(e1);
  double v = inv * d.dot(qv);
  if (v < 0 || u + v > 1) return false;
  double along = inv * e2.dot(qv);
  return along >= 0 && along <= 1;
}

}  // namespace

bool triangles_intersect(const Eigen::Vector3d* a, const Eigen::Vector3d* b) {
  for (int k = 0; k < 3; ++k) {
    if (segment_hits_triangle(a[k], a[(k + 1) % 3], b)) return true;
    if (segment_hits_triangle(b[k], b[(k + 1) % 3], a)) return true;
  }
  return false;
}

double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  // Closest point by Voronoi regions (Ericson, Real-Time Collision Detection 5.1.5).
  Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  Eigen::Vector3d bp = p - b;
  double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  Eigen::Vector3d cp = p - c;
  double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
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

namespace {

//! Whether triangles a and b (not sharing a vertex) intersect: boxes first,
//! then the exact test.
bool triangle_pair_intersects(const MeshTriangles& triangles, size_t a, size_t b) {
  for (int i : triangles.corners[a])
    for (int j : triangles.corners[b])
      if (i == j) return false;
  Eigen::Vector3d pa[3], pb[3];
  for (int k = 0; k < 3; ++k) pa[k] = triangles.corner(a, k), pb[k] = triangles.corner(b, k);
  Eigen::Vector3d lo_a = pa[0].cwiseMin(pa[1]).cwiseMin(pa[2]), hi_a = pa[0].cwiseMax(pa[1]).cwiseMax(pa[2]);
  Eigen::Vector3d lo_b = pb[0].cwiseMin(pb[1]).cwiseMin(pb[2]), hi_b = pb[0].cwiseMax(pb[1]).cwiseMax(pb[2]);
  if ((lo_a.array() > hi_b.array()).any() || (lo_b.array() > hi_a.array()).any()) return false;
  return triangles_intersect(pa, pb);
}

}  // namespace

std::vector<std::pair<int, int>> intersecting_face_pairs(const QuadMesh& mesh) {
  MeshTriangles triangles = triangulate(mesh);
  if (triangles.size() == 0) return {};
  double longest = 0;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, (triangles.corner(t, k) - triangles.corner(t, (k + 1) % 3)).norm());
      low = low.cwiseMin(triangles.corner(t, k));
    }
  // Cells of 4/3 the longest edge: every point of a triangle lies within 2/3
  // of it from the centroid, so touching triangles sit in neighbouring cells.
  double cell = std::max(4.0 / 3.0 * longest, 1e-12);
  constexpr int kBits = 21;
  Eigen::Vector3d high = low;
  for (const Eigen::Vector3d& p : triangles.positions) high = high.cwiseMax(p);
  cell = std::max(cell, (high - low).maxCoeff() / double((1 << kBits) - 3));
  auto cell_of = [&](const Eigen::Vector3d& p) {
    Eigen::Vector3d c = (p - low) / cell;
    return std::array<uint64_t, 3>{uint64_t(c.x()) + 1, uint64_t(c.y()) + 1, uint64_t(c.z()) + 1};
  };
  auto key = [](uint64_t x, uint64_t y, uint64_t z) { return x << (2 * kBits) | y << kBits | z; };
  // One entry a triangle, sorted by cell: runs of equal keys are the cells.
  std::vector<std::pair<uint64_t, uint32_t>> entries(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    auto c = cell_of(triangles.centroid(t));
    entries[t] = {key(c[0], c[1], c[2]), uint32_t(t)};
  }
  std::sort(entries.begin(), entries.end());
  std::unordered_map<uint64_t, std::pair<uint32_t, uint32_t>> runs;
  for (size_t begin = 0; begin < entries.size();) {
    size_t end = begin;
    while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
    runs.emplace(entries[begin].first, std::make_pair(uint32_t(begin), uint32_t(end)));
    begin = end;
  }
  std::set<std::pair<int, int>> pairs;
  auto test = [&](uint32_t a, uint32_t b) {
    int fa = triangles.face[a], fb = triangles.face[b];
    if (fa == fb) return;
    std::pair<int, int> pair{std::min(fa, fb), std::max(fa, fb)};
    if (!pairs.count(pair) && triangle_pair_intersects(triangles, a, b)) pairs.insert(pair);
  };
  for (const auto& [k, run] : runs) {
    uint64_t x = k >> (2 * kBits), y = (k >> kBits) & ((1u << kBits) - 1), z = k & ((1u << kBits) - 1);
    for (uint64_t dx = 0; dx < 3; ++dx)
      for (uint64_t dy = 0; dy < 3; ++dy)
        for (uint64_t dz = 0; dz < 3; ++dz) {
          uint64_t other = key(x + dx - 1, y + dy - 1, z + dz - 1);
          if (other < k) continue;  // each pair of cells once
          auto found = runs.find(other);
          if (found == runs.end()) continue;
          for (uint32_t m = run.first; m < run.second; ++m)
            for (uint32_t n = other == k ? m + 1 : found->second.first; n < found->second.second; ++n)
              test(entries[m].second, entries[n].second);
        }
  }
  return {pairs.begin(), pairs.end()};
}

}  // namespace mcquad
