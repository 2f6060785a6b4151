#include "mesh/face_intersections.h"

#include <algorithm>

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

namespace {

//! Whether all corners of triangle t lie strictly on one side of the plane
//! of triangle p: then they cannot meet (the cheap rejection that most
//! neighbouring pairs on a smooth surface take).
bool strictly_one_side(const Eigen::Vector3d* p, const Eigen::Vector3d* t) {
  Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
  double d0 = normal.dot(t[0] - p[0]), d1 = normal.dot(t[1] - p[0]), d2 = normal.dot(t[2] - p[0]);
  return (d0 > 0 && d1 > 0 && d2 > 0) || (d0 < 0 && d1 < 0 && d2 < 0);
}

}  // namespace

bool triangles_intersect(const Eigen::Vector3d* a, const Eigen::Vector3d* b) {
  if (strictly_one_side(a, b) || strictly_one_side(b, a)) return false;
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
  return intersecting_face_pairs(triangulate(mesh));
}

std::vector<std::pair<int, int>> intersecting_face_pairs(const MeshTriangles& triangles,
                                                         const std::vector<char>* only_faces) {
  size_t n = triangles.size();
  if (n == 0) return {};
  // Boxes in floats, rounded outward (half the memory at millions of
  // triangles; the exact test after them is in doubles).
  std::vector<Eigen::Vector3f> lo(n), hi(n);
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  double extent = 0;
  for (size_t t = 0; t < n; ++t) {
    Eigen::Vector3d l = triangles.corner(t, 0).cwiseMin(triangles.corner(t, 1)).cwiseMin(triangles.corner(t, 2));
    Eigen::Vector3d h = triangles.corner(t, 0).cwiseMax(triangles.corner(t, 1)).cwiseMax(triangles.corner(t, 2));
    for (int k = 0; k < 3; ++k) {
      lo[t][k] = std::nextafter(float(l[k]), -INFINITY);
      hi[t][k] = std::nextafter(float(h[k]), INFINITY);
    }
    low = low.cwiseMin(l);
    high = high.cwiseMax(h);
    extent += (h - l).maxCoeff();
  }
  // Each triangle goes into every grid cell its box overlaps. Cells of three
  // times the mean box extent keep that to a few cells a triangle, however
  // uneven the edge lengths (a cell of the longest edge puts thousands of
  // small triangles together next to one long one).
  constexpr int kBits = 21;
  double cell = std::max({3.0 * extent / double(n), (high - low).maxCoeff() / double((1 << kBits) - 4), 1e-12});
  using Cell = Eigen::Matrix<uint32_t, 3, 1>;
  auto cell_of = [&](const Eigen::Vector3f& p) {
    Eigen::Vector3d c = ((p.cast<double>() - low) / cell).cwiseMax(0.0);
    return Cell(uint32_t(c.x()), uint32_t(c.y()), uint32_t(c.z()));
  };
  auto key = [](const Cell& c) { return uint64_t(c.x()) << (2 * kBits) | uint64_t(c.y()) << kBits | c.z(); };
  auto for_each_cell = [&](size_t t, auto&& visit) {
    auto a = cell_of(lo[t]), b = cell_of(hi[t]);
    for (uint32_t x = a.x(); x <= b.x(); ++x)
      for (uint32_t y = a.y(); y <= b.y(); ++y)
        for (uint32_t z = a.z(); z <= b.z(); ++z) visit(key(Cell(x, y, z)));
  };
  // With `only_faces`, just the cells those faces touch matter: the other
  // triangles enter the grid only where they share such a cell.
  auto is_wanted = [&](size_t t) { return !only_faces || (*only_faces)[size_t(triangles.face[t])]; };
  std::vector<uint64_t> wanted_cells;
  if (only_faces) {
    for (size_t t = 0; t < n; ++t)
      if (is_wanted(t)) for_each_cell(t, [&](uint64_t k) { wanted_cells.push_back(k); });
    std::sort(wanted_cells.begin(), wanted_cells.end());
    wanted_cells.erase(std::unique(wanted_cells.begin(), wanted_cells.end()), wanted_cells.end());
  }
  // The cell of each box's low corner: the cell of two boxes' overlap's low
  // corner is their componentwise maximum (cells are monotone per axis).
  std::vector<Cell> low_cell(n);
  for (size_t t = 0; t < n; ++t) low_cell[t] = cell_of(lo[t]);
  std::vector<std::pair<uint64_t, uint32_t>> entries;
  entries.reserve(only_faces ? 8 * wanted_cells.size() : 2 * n);
  for (size_t t = 0; t < n; ++t)
    for_each_cell(t, [&](uint64_t k) {
      if (!only_faces || std::binary_search(wanted_cells.begin(), wanted_cells.end(), k))
        entries.emplace_back(k, uint32_t(t));
    });
  std::sort(entries.begin(), entries.end());
  std::vector<uint32_t> runs;  // where each cell's run of entries begins
  for (size_t k = 0; k < entries.size(); ++k)
    if (k == 0 || entries[k].first != entries[k - 1].first) runs.push_back(uint32_t(k));
  runs.push_back(uint32_t(entries.size()));
  std::vector<std::pair<int, int>> pairs;
  // Threads pay off only on large meshes (the evolution's guard calls this
  // every step, often with a few faces).
#pragma omp parallel if (entries.size() > 8192)
  {
    std::vector<std::pair<int, int>> found;
    long cells = long(runs.size()) - 1;
    std::vector<uint32_t> in_cell;
#pragma omp for schedule(dynamic, 64)
    for (long r = 0; r < cells; ++r) {
      uint64_t here = entries[runs[size_t(r)]].first;
      // Sweep along x within the cell: only boxes overlapping in x pair up.
      in_cell.clear();
      for (size_t m = runs[size_t(r)]; m < runs[size_t(r) + 1]; ++m) in_cell.push_back(entries[m].second);
      std::sort(in_cell.begin(), in_cell.end(), [&](uint32_t a, uint32_t b) { return lo[a].x() < lo[b].x(); });
      for (size_t m = 0; m < in_cell.size(); ++m)
        for (size_t k = m + 1; k < in_cell.size() && lo[in_cell[k]].x() <= hi[in_cell[m]].x(); ++k) {
          uint32_t a = in_cell[m], b = in_cell[k];
          int fa = triangles.face[a], fb = triangles.face[b];
          if (fa == fb || (only_faces && !(*only_faces)[size_t(fa)] && !(*only_faces)[size_t(fb)])) continue;
          // A pair of boxes overlaps in several cells; it is tested in the
          // one holding the low corner of the overlap.
          if ((lo[a].cwiseMax(lo[b]).array() > hi[a].cwiseMin(hi[b]).array()).any()) continue;
          if (key(low_cell[a].cwiseMax(low_cell[b])) != here) continue;
          if (triangle_pair_intersects(triangles, a, b)) found.emplace_back(std::min(fa, fb), std::max(fa, fb));
        }
    }
#pragma omp critical
    pairs.insert(pairs.end(), found.begin(), found.end());
  }
  // A quad is two triangles, so a pair of faces can be found twice.
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace mcquad
