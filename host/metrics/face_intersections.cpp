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

std::vector<std::pair<int, int>> intersecting_face_pairs(const QuadMesh& mesh) {
  struct Triangle {
    Eigen::Vector3d p[3];
    int face;
    std::array<int, 3> v;
  };
  std::vector<Triangle> triangles;
  double longest = 0;
  for (auto f : mesh.faces()) {
    std::vector<QuadMesh::VertexHandle> vs;
    for (auto v : mesh.fv_range(f)) vs.push_back(v);
    for (size_t k = 1; k + 1 < vs.size(); ++k) {
      Triangle t;
      int ids[3] = {vs[0].idx(), vs[k].idx(), vs[k + 1].idx()};
      for (int j = 0; j < 3; ++j) {
        const auto& q = mesh.point(vs[j == 0 ? 0 : k + j - 1]);
        t.p[j] = Eigen::Vector3d(q[0], q[1], q[2]);
        t.v[j] = ids[j];
      }
      t.face = f.idx();
      for (int j = 0; j < 3; ++j) longest = std::max(longest, (t.p[j] - t.p[(j + 1) % 3]).norm());
      triangles.push_back(t);
    }
  }
  if (triangles.empty()) return {};
  double cell = std::max(longest, 1e-12);
  auto key = [](long x, long y, long z) { return (x * 73856093L) ^ (y * 19349663L) ^ (z * 83492791L); };
  std::unordered_map<long, std::vector<int>> grid;
  auto cell_of = [&](double v) { return long(std::floor(v / cell)); };
  for (size_t i = 0; i < triangles.size(); ++i) {
    Eigen::Vector3d lo = triangles[i].p[0].cwiseMin(triangles[i].p[1]).cwiseMin(triangles[i].p[2]);
    Eigen::Vector3d hi = triangles[i].p[0].cwiseMax(triangles[i].p[1]).cwiseMax(triangles[i].p[2]);
    for (long x = cell_of(lo.x()); x <= cell_of(hi.x()); ++x)
      for (long y = cell_of(lo.y()); y <= cell_of(hi.y()); ++y)
        for (long z = cell_of(lo.z()); z <= cell_of(hi.z()); ++z) grid[key(x, y, z)].push_back(int(i));
  }
  std::set<std::pair<int, int>> pairs;
  for (const auto& [k, members] : grid) {
    for (size_t m = 0; m < members.size(); ++m) {
      for (size_t n = m + 1; n < members.size(); ++n) {
        const Triangle& a = triangles[members[m]];
        const Triangle& b = triangles[members[n]];
        if (a.face == b.face) continue;
        std::pair<int, int> pair{std::min(a.face, b.face), std::max(a.face, b.face)};
        if (pairs.count(pair)) continue;
        bool shared = false;
        for (int i : a.v)
          for (int j : b.v) shared = shared || i == j;
        if (shared) continue;
        Eigen::Vector3d lo_a = a.p[0].cwiseMin(a.p[1]).cwiseMin(a.p[2]), hi_a = a.p[0].cwiseMax(a.p[1]).cwiseMax(a.p[2]);
        Eigen::Vector3d lo_b = b.p[0].cwiseMin(b.p[1]).cwiseMin(b.p[2]), hi_b = b.p[0].cwiseMax(b.p[1]).cwiseMax(b.p[2]);
        if ((lo_a.array() > hi_b.array()).any() || (lo_b.array() > hi_a.array()).any()) continue;
        if (triangles_intersect(a.p, b.p)) pairs.insert(pair);
      }
    }
  }
  return {pairs.begin(), pairs.end()};
}

}  // namespace mcquad
