#include "metrics/mesh_statistics.h"

#include <numeric>
#include <set>

namespace mcquad {

std::vector<int> irregular_vertices(const QuadMesh& mesh) {
  std::vector<int> out;
  for (auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    if (!is_regular_vertex(mesh, v)) out.push_back(v.idx());
  }
  return out;
}

std::vector<Eigen::Vector3d> boundary_loop_centres(const QuadMesh& mesh) {
  std::vector<Eigen::Vector3d> centres;
  std::set<int> seen;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen.count(h.idx())) continue;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int corners = 0;
    auto walk = h;
    do {
      seen.insert(walk.idx());
      sum += point_of(mesh, mesh.to_vertex_handle(walk));
      ++corners;
      walk = mesh.next_halfedge_handle(walk);
    } while (walk != h);
    centres.emplace_back(sum / corners);
  }
  return centres;
}

MeshStatistics mesh_statistics(const QuadMesh& mesh) {
  MeshStatistics s;
  s.vertices = mesh.n_vertices();
  s.faces = mesh.n_faces();
  s.edges = mesh.n_edges();
  for (auto f : mesh.faces()) s.quads += mesh.valence(f) == 4;
  s.quad_fraction = s.faces ? double(s.quads) / s.faces : 0.0;
  s.euler_characteristic = long(s.vertices) - long(s.edges) + long(s.faces);
  s.irregular_vertices = irregular_vertices(mesh).size();
  for (auto v : mesh.vertices()) s.non_manifold_vertices += !mesh.is_manifold(v);
  s.boundary_loops = boundary_loop_centres(mesh).size();
  std::vector<int> component(mesh.n_vertices(), -1);
  for (auto start : mesh.vertices()) {
    if (component[start.idx()] >= 0) continue;
    std::vector<QuadMesh::VertexHandle> stack{start};
    component[start.idx()] = int(s.components);
    while (!stack.empty()) {
      auto v = stack.back();
      stack.pop_back();
      for (auto w : mesh.vv_range(v)) {
        if (component[w.idx()] < 0) {
          component[w.idx()] = int(s.components);
          stack.push_back(w);
        }
      }
    }
    ++s.components;
  }
  return s;
}

nlohmann::json to_json(const MeshStatistics& s) {
  return {{"vertices", s.vertices},
          {"faces", s.faces},
          {"edges", s.edges},
          {"quad_fraction", s.quad_fraction},
          {"euler_characteristic", s.euler_characteristic},
          {"boundary_loops", s.boundary_loops},
          {"components", s.components},
          {"irregular_vertices", s.irregular_vertices},
          {"non_manifold_vertices", s.non_manifold_vertices}};
}

}  // namespace mcquad
