#include "mesh/folds.h"

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace mcquad {

bool is_folded(const QuadMesh& mesh, QuadMesh::EdgeHandle edge) {
  if (mesh.is_boundary(edge)) return false;
  auto f0 = mesh.face_handle(mesh.halfedge_handle(edge, 0));
  auto f1 = mesh.face_handle(mesh.halfedge_handle(edge, 1));
  return normals_fold(face_vector_area(mesh, f0), face_vector_area(mesh, f1));
}

size_t folded_edges(const QuadMesh& mesh) {
  size_t folded = 0;
  for (auto e : mesh.edges()) folded += is_folded(mesh, e);
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
    for (auto e : mesh.edges()) {
      if (mesh.is_boundary(e) || !is_folded(mesh, e)) continue;
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
