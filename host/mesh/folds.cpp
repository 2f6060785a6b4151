#include "mesh/folds.h"

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace mcquad {

namespace {

//! Every face's vector area, by face index: a scan of all edges computes
//! each face's once instead of once per edge (the knot's initial mesh
//! spent 18 ms in one pass of relax_folds doing it per edge).
std::vector<Eigen::Vector3d> face_vector_areas(const QuadMesh& mesh) {
  std::vector<Eigen::Vector3d> areas(mesh.n_faces());
  for (auto f : mesh.faces()) areas[size_t(f.idx())] = face_vector_area(mesh, f);
  return areas;
}

//! Whether an interior edge's two faces fold, their vector areas given by `area_of(face)`.
template <typename AreaOf>
bool edge_folds(const QuadMesh& mesh, QuadMesh::EdgeHandle edge, const AreaOf& area_of) {
  if (mesh.is_boundary(edge)) return false;
  return normals_fold(area_of(mesh.face_handle(mesh.halfedge_handle(edge, 0))),
                      area_of(mesh.face_handle(mesh.halfedge_handle(edge, 1))));
}

//! edge_folds with the faces' vector areas computed beforehand.
bool is_folded(const QuadMesh& mesh, const std::vector<Eigen::Vector3d>& areas, QuadMesh::EdgeHandle edge) {
  return edge_folds(mesh, edge, [&](QuadMesh::FaceHandle f) { return areas[size_t(f.idx())]; });
}

}  // namespace

bool is_folded(const QuadMesh& mesh, QuadMesh::EdgeHandle edge) {
  return edge_folds(mesh, edge, [&](QuadMesh::FaceHandle f) { return face_vector_area(mesh, f); });
}

size_t folded_edges(const QuadMesh& mesh) {
  const std::vector<Eigen::Vector3d> areas = face_vector_areas(mesh);
  size_t folded = 0;
  for (auto e : mesh.edges()) folded += is_folded(mesh, areas, e);
  return folded;
}

void relax_vertices(QuadMesh& mesh, const std::set<int>& region) {
  std::vector<std::pair<int, QuadMesh::Point>> moved;
  for (int i : region) {
    auto v = mesh.vertex_handle(i);
    if (mesh.is_boundary(v)) continue;
    QuadMesh::Point mean(0, 0, 0);
    int count = 0;
    for (auto w : mesh.vv_range(v)) {
      mean += mesh.point(w);
      ++count;
    }
    moved.emplace_back(i, 0.5 * mesh.point(v) + 0.5 * mean / count);
  }
  for (const auto& [i, p] : moved) mesh.set_point(mesh.vertex_handle(i), p);
}

std::set<int> corners_of(const QuadMesh& mesh, const std::vector<int>& faces) {
  std::set<int> corners;
  for (int f : faces)
    for (auto v : mesh.fv_range(mesh.face_handle(f))) corners.insert(v.idx());
  return corners;
}

void grow_region(const QuadMesh& mesh, std::set<int>& region, int rings) {
  for (int ring = 0; ring < rings; ++ring) {
    std::set<int> grown = region;
    for (int i : region)
      for (auto w : mesh.vv_range(mesh.vertex_handle(i))) grown.insert(w.idx());
    region.swap(grown);
  }
}

void relax_folds(QuadMesh& mesh, int widening_rings) {
  for (int round = 0; round < 50; ++round) {
    std::set<int> region;
    const std::vector<Eigen::Vector3d> areas = face_vector_areas(mesh);
    for (auto e : mesh.edges()) {
      if (!is_folded(mesh, areas, e)) continue;
      for (int side = 0; side < 2; ++side)
        for (auto v : mesh.fv_range(mesh.face_handle(mesh.halfedge_handle(e, side))))
          for (auto w : mesh.vv_range(v)) region.insert(w.idx());
    }
    if (region.empty()) return;
    grow_region(mesh, region, std::min(widening_rings, round / 10));
    relax_vertices(mesh, region);
  }
}

}  // namespace mcquad
