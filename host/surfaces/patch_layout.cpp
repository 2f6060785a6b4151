#include "surfaces/patch_layout.h"

#include <Eigen/Geometry>
#include <array>
#include <numeric>
#include <queue>
#include <string>

#include "core/errors.h"

namespace mcquad {
namespace {

using Cell = Eigen::Vector2i;
using Corners = std::array<Cell, 4>;  // grid coordinates of a face's corners, in halfedge order

//! The halfedge leaving b = to(h) straight ahead of h, through a regular
//! interior vertex b (two turns around b from b->a).
QuadMesh::HalfedgeHandle straight_on(const QuadMesh& mesh, QuadMesh::HalfedgeHandle h) {
  auto out = mesh.cw_rotated_halfedge_handle(mesh.opposite_halfedge_handle(h));
  return mesh.cw_rotated_halfedge_handle(out);
}

//! Marks the edges of every separatrix; returns how many irregular vertices
//! started them.
size_t trace_separatrices(const QuadMesh& mesh, std::vector<char>& marked) {
  size_t irregular = 0;
  for (auto v : mesh.vertices()) {
    if (is_regular_vertex(mesh, v)) continue;
    ++irregular;
    for (auto start : mesh.voh_range(v)) {
      QuadMesh::HalfedgeHandle h = start;
      while (!mesh.is_boundary(mesh.edge_handle(h)) && !marked[size_t(mesh.edge_handle(h).idx())]) {
        marked[size_t(mesh.edge_handle(h).idx())] = 1;
        auto b = mesh.to_vertex_handle(h);
        if (mesh.is_boundary(b) || mesh.valence(b) != 4) break;
        h = straight_on(mesh, h);
      }
    }
  }
  return irregular;
}

//! Faces connected across edges that are neither separatrices nor boundary.
std::vector<std::vector<int>> flood_regions(const QuadMesh& mesh, const std::vector<char>& marked) {
  std::vector<int> region_of(mesh.n_faces(), -1);
  std::vector<std::vector<int>> regions;
  for (auto seed : mesh.faces()) {
    if (region_of[size_t(seed.idx())] >= 0) continue;
    regions.emplace_back();
    std::vector<QuadMesh::FaceHandle> stack{seed};
    region_of[size_t(seed.idx())] = int(regions.size() - 1);
    while (!stack.empty()) {
      auto f = stack.back();
      stack.pop_back();
      regions.back().push_back(f.idx());
      for (auto h : mesh.fh_range(f)) {
        auto e = mesh.edge_handle(h);
        if (mesh.is_boundary(e) || marked[size_t(e.idx())]) continue;
        auto g = mesh.face_handle(mesh.opposite_halfedge_handle(h));
        if (region_of[size_t(g.idx())] >= 0) continue;
        region_of[size_t(g.idx())] = region_of[size_t(f.idx())];
        stack.push_back(g);
      }
    }
  }
  return regions;
}

std::array<QuadMesh::HalfedgeHandle, 4> face_halfedges(const QuadMesh& mesh, QuadMesh::FaceHandle f) {
  std::array<QuadMesh::HalfedgeHandle, 4> h;
  h[0] = mesh.halfedge_handle(f);
  for (int k = 1; k < 4; ++k) h[size_t(k)] = mesh.next_halfedge_handle(h[size_t(k - 1)]);
  return h;
}

Cell rotate_left(const Cell& d) { return Cell(-d.y(), d.x()); }

//! Integer grid coordinates for the corners of a region's faces, unrolled by
//! a breadth-first walk, and the translations by which the walk found the
//! region closing on itself (its periods).
struct Unrolled {
  std::vector<Corners> corners;  // per region face
  std::vector<Cell> periods;
  bool consistent = true;
};

Unrolled unroll_region(const QuadMesh& mesh, const std::vector<int>& faces, const std::vector<int>& local_index,
                       const std::vector<char>& marked) {
  Unrolled result;
  result.corners.resize(faces.size());
  std::vector<char> placed(faces.size(), 0);
  result.corners[0] = {Cell(0, 0), Cell(1, 0), Cell(1, 1), Cell(0, 1)};
  placed[0] = 1;
  std::queue<size_t> queue;
  queue.push(0);
  while (!queue.empty()) {
    size_t local = queue.front();
    queue.pop();
    auto hs = face_halfedges(mesh, QuadMesh::FaceHandle(faces[local]));
    for (int k = 0; k < 4; ++k) {
      auto e = mesh.edge_handle(hs[size_t(k)]);
      if (mesh.is_boundary(e) || marked[size_t(e.idx())]) continue;
      const Cell& a = result.corners[local][size_t(k)];
      const Cell& b = result.corners[local][size_t((k + 1) % 4)];
      // The neighbour's corners from the opposite halfedge b->a on: b, a, x, y.
      auto opposite = mesh.opposite_halfedge_handle(hs[size_t(k)]);
      auto g = mesh.face_handle(opposite);
      size_t g_local = size_t(local_index[size_t(g.idx())]);
      auto gh = face_halfedges(mesh, g);
      int start = int(std::find(gh.begin(), gh.end(), opposite) - gh.begin());
      Cell d = a - b;
      Cell x = a + rotate_left(d);
      Corners expected;
      expected[size_t(start)] = b;
      expected[size_t((start + 1) % 4)] = a;
      expected[size_t((start + 2) % 4)] = x;
      expected[size_t((start + 3) % 4)] = x - d;
      if (!placed[g_local]) {
        result.corners[g_local] = expected;
        placed[g_local] = 1;
        queue.push(g_local);
        continue;
      }
      Cell shift = result.corners[g_local][size_t(start)] - b;
      for (int c = 0; c < 4; ++c)
        if (result.corners[g_local][size_t(c)] - expected[size_t(c)] != shift) result.consistent = false;
      if (shift != Cell(0, 0)) result.periods.push_back(shift);
    }
  }
  return result;
}

long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
long floor_mod(long a, long b) { return a - floor_div(a, b) * b; }

//! The lattice of periods in Hermite normal form: rows (a, s) and (0, b),
//! a, b >= 0 and 0 <= s < b where b > 0.
struct Lattice {
  long a = 0, s = 0, b = 0;
};

Lattice reduce_periods(const std::vector<Cell>& periods) {
  Lattice l;
  for (const Cell& p : periods) {
    long x = p.x(), y = p.y();
    while (x != 0) {  // Euclid on the first column, carrying the second
      long q = l.a / x;
      l.a -= q * x;
      l.s -= q * y;
      std::swap(l.a, x);
      std::swap(l.s, y);
    }
    l.b = std::gcd(l.b, std::abs(y));
  }
  if (l.a < 0) l.a = -l.a, l.s = -l.s;
  if (l.b > 0) l.s = floor_mod(l.s, l.b);
  return l;
}

//! Builds the region's vertex grid and its faces' corner parameters from the
//! unrolled coordinates; false when the region is not a clean grid.
bool build_grid(const QuadMesh& mesh, const std::vector<int>& faces, const Unrolled& unrolled, PatchRegion& region,
                std::vector<Corners>& corners) {
  if (!unrolled.consistent) return false;
  Lattice lattice = reduce_periods(unrolled.periods);
  if (lattice.a > 0 && lattice.b == 0 && lattice.s != 0) return false;  // a helical cylinder
  corners = unrolled.corners;
  // Move every face into the fundamental domain [0, a) x [0, b) of the periods.
  for (Corners& c : corners) {
    Cell low = c[0].cwiseMin(c[1]).cwiseMin(c[2]).cwiseMin(c[3]);
    Cell shift(0, 0);
    if (lattice.a > 0) {
      long turns = floor_div(low.x(), lattice.a);
      shift -= Cell(int(turns * lattice.a), int(turns * lattice.s));
    }
    if (lattice.b > 0) shift.y() -= int(floor_div(low.y() + shift.y(), lattice.b) * lattice.b);
    for (Cell& corner : c) corner += shift;
  }
  Cell low(INT32_MAX, INT32_MAX), high(INT32_MIN, INT32_MIN);
  for (const Corners& c : corners)
    for (const Cell& corner : c) low = low.cwiseMin(corner), high = high.cwiseMax(corner);
  for (Corners& c : corners)  // clamped directions start at 0
    for (Cell& corner : c) corner -= Cell(lattice.a > 0 ? 0 : low.x(), lattice.b > 0 ? 0 : low.y());
  high -= Cell(lattice.a > 0 ? 0 : low.x(), lattice.b > 0 ? 0 : low.y());
  region.periodic_u = lattice.a > 0 && lattice.s == 0;
  region.periodic_v = lattice.b > 0;
  int faces_u = lattice.a > 0 ? int(lattice.a) : high.x();
  int faces_v = lattice.b > 0 ? int(lattice.b) : high.y();
  if (size_t(faces_u) * size_t(faces_v) != faces.size()) return false;
  region.columns = region.periodic_u ? faces_u : faces_u + 1;
  region.rows = region.periodic_v ? faces_v : faces_v + 1;
  region.vertices.assign(size_t(region.columns) * size_t(region.rows), -1);
  std::vector<char> cell_used(faces.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    Cell low_corner = corners[f][0].cwiseMin(corners[f][1]).cwiseMin(corners[f][2]).cwiseMin(corners[f][3]);
    if (low_corner.x() < 0 || low_corner.y() < 0 || low_corner.x() >= faces_u || low_corner.y() >= faces_v)
      return false;
    char& used = cell_used[size_t(low_corner.y()) * size_t(faces_u) + size_t(low_corner.x())];
    if (used) return false;
    used = 1;
    auto hs = face_halfedges(mesh, QuadMesh::FaceHandle(faces[f]));
    for (int k = 0; k < 4; ++k) {
      int i = corners[f][size_t(k)].x(), j = corners[f][size_t(k)].y();
      if (region.periodic_u) i %= region.columns;
      if (region.periodic_v) j %= region.rows;
      int& slot = region.vertices[size_t(j) * size_t(region.columns) + size_t(i)];
      int v = mesh.from_vertex_handle(hs[size_t(k)]).idx();
      if (slot >= 0 && slot != v) return false;
      slot = v;
    }
  }
  return std::find(region.vertices.begin(), region.vertices.end(), -1) == region.vertices.end();
}

//! Corner parameters in the order of mesh.fv_range(f), from halfedge order.
std::array<Eigen::Vector2d, 4> in_face_order(const QuadMesh& mesh, QuadMesh::FaceHandle f, const Corners& corners) {
  auto hs = face_halfedges(mesh, f);
  std::array<Eigen::Vector2d, 4> result;
  int k = 0;
  for (auto v : mesh.fv_range(f)) {
    for (int c = 0; c < 4; ++c)
      if (mesh.from_vertex_handle(hs[size_t(c)]) == v) result[size_t(k)] = corners[size_t(c)].cast<double>();
    ++k;
  }
  return result;
}

}  // namespace

namespace {

//! Unit normal of the mesh at v: the sum of its faces' vector areas.
Eigen::Vector3d vertex_normal(const QuadMesh& mesh, QuadMesh::VertexHandle v) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto f : mesh.vf_range(v)) sum += quad_vector_area(face_corners(mesh, f));
  return sum.normalized();
}

}  // namespace

Eigen::Vector3d grid_tangent(const QuadMesh& mesh, QuadMesh::VertexHandle p, QuadMesh::VertexHandle q) {
  auto h = mesh.find_halfedge(p, q);
  Eigen::Vector3d edge = point_of(mesh, q) - point_of(mesh, p);
  if (!h.is_valid()) return edge;
  if (!mesh.is_boundary(p)) {
    // The first Fourier harmonic of the edge ring (the tangent rule of
    // Catmull-Clark limit surfaces, without the face points):
    // t_k = 2/n sum_j cos(2 pi (j - k) / n) e_j. At valence 4 it is the
    // central difference (q - r) / 2. Its point at other valences: the
    // tangents of the n seams satisfy t[k-1] + t[k+1] = 2 cos(2 pi / n) t[k],
    // so where two regions meet along seam k, their cross tangents add up to
    // a multiple of the seam's own tangent, the condition for tangent-plane
    // continuity, at the vertex and to first order beside it.
    std::vector<Eigen::Vector3d> ring;
    size_t k = 0;
    for (auto out = h;;) {
      if (out == h) k = ring.size();
      ring.emplace_back(point_of(mesh, mesh.to_vertex_handle(out)) - point_of(mesh, p));
      out = mesh.cw_rotated_halfedge_handle(out);
      if (out == h) break;
    }
    const size_t n = ring.size();
    Eigen::Vector3d tangent = Eigen::Vector3d::Zero();
    for (size_t j = 0; j < n; ++j) tangent += std::cos(2 * M_PI * double((j + n - k) % n) / double(n)) * ring[j];
    tangent *= 2.0 / double(n);
    if (n == 4) return tangent;
    Eigen::Vector3d normal = vertex_normal(mesh, p);  // exactly in the tangent plane shared by all regions
    return tangent - tangent.dot(normal) * normal;
  }
  if (mesh.is_boundary(mesh.edge_handle(h)) && mesh.valence(p) == 3) {
    // Along a smooth rim: central difference with the rim's other neighbour.
    for (auto r : mesh.vv_range(p))
      if (r != q && mesh.is_boundary(mesh.edge_handle(mesh.find_halfedge(p, r))))
        return 0.5 * (point_of(mesh, q) - point_of(mesh, r));
  }
  // Elsewhere on the boundary: the edge laid into the tangent plane, the
  // same for every region that meets at p.
  Eigen::Vector3d normal = vertex_normal(mesh, p);
  return edge - edge.dot(normal) * normal;
}

PatchLayout decompose_into_patches(const QuadMesh& mesh) {
  for (auto f : mesh.faces())
    if (mesh.valence(f) != 4)
      throw UnsupportedError("surfaces: face " + std::to_string(f.idx()) + " has " + std::to_string(mesh.valence(f)) +
                             " corners; only all-quad meshes can be decomposed into B-spline patches");
  PatchLayout layout;
  std::vector<char> marked(mesh.n_edges(), 0);
  layout.irregular_vertices = trace_separatrices(mesh, marked);
  layout.separatrix_edges = size_t(std::count(marked.begin(), marked.end(), 1));
  layout.face_region.assign(mesh.n_faces(), -1);
  layout.face_corner_parameters.resize(mesh.n_faces());
  std::vector<int> local_index(mesh.n_faces(), -1);
  for (const std::vector<int>& faces : flood_regions(mesh, marked)) {
    for (size_t k = 0; k < faces.size(); ++k) local_index[size_t(faces[k])] = int(k);
    PatchRegion region;
    std::vector<Corners> corners;
    if (build_grid(mesh, faces, unroll_region(mesh, faces, local_index, marked), region, corners)) {
      region.faces = faces;
      for (size_t k = 0; k < faces.size(); ++k) {
        QuadMesh::FaceHandle f(faces[k]);
        layout.face_region[size_t(faces[k])] = int(layout.regions.size());
        layout.face_corner_parameters[size_t(faces[k])] = in_face_order(mesh, f, corners[k]);
      }
      layout.regions.push_back(std::move(region));
      continue;
    }
    for (int face : faces) {  // not a clean grid: one region per face
      QuadMesh::FaceHandle f(face);
      auto hs = face_halfedges(mesh, f);
      PatchRegion single;
      single.columns = single.rows = 2;
      single.faces = {face};
      const Corners unit = {Cell(0, 0), Cell(1, 0), Cell(1, 1), Cell(0, 1)};
      single.vertices.resize(4);
      for (int k = 0; k < 4; ++k)
        single.vertices[size_t(unit[size_t(k)].y() * 2 + unit[size_t(k)].x())] =
            mesh.from_vertex_handle(hs[size_t(k)]).idx();
      layout.face_region[size_t(face)] = int(layout.regions.size());
      layout.face_corner_parameters[size_t(face)] = in_face_order(mesh, f, unit);
      layout.regions.push_back(std::move(single));
      layout.single_face_fallbacks += 1;
    }
  }
  return layout;
}

}  // namespace mcquad
