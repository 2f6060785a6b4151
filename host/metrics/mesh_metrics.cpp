#include "metrics/mesh_metrics.h"

#include <set>

#include "evolution/shared_math.h"
#include "metrics/face_intersections.h"
#include "skeleton/bone_assignment.h"

namespace mcquad {

std::vector<int> irregular_vertices(const QuadMesh& mesh) {
  std::vector<int> out;
  for (auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    size_t regular = mesh.is_boundary(v) ? 3 : 4;
    if (mesh.valence(v) != regular) out.push_back(v.idx());
  }
  return out;
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
  std::set<int> seen;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen.count(h.idx())) continue;
    ++s.boundary_loops;
    auto walk = h;
    do {
      seen.insert(walk.idx());
      walk = mesh.next_halfedge_handle(walk);
    } while (walk != h);
  }
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

size_t inward_faces(const QuadMesh& mesh, const SkeletonGraph& skeleton) {
  size_t inward = 0;
  for (auto f : mesh.faces()) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> corners;
    for (auto v : mesh.fv_range(f)) {
      const auto& p = mesh.point(v);
      corners.emplace_back(p[0], p[1], p[2]);
      centroid += corners.back();
    }
    centroid /= double(corners.size());
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < corners.size(); ++k) normal += corners[k].cross(corners[(k + 1) % corners.size()]);
    double best = INFINITY;
    Eigen::Vector3d nearest = centroid;
    for (const auto& e : skeleton.edges) {
      double t;
      const auto& a = skeleton.positions[e[0]];
      const auto& b = skeleton.positions[e[1]];
      double d = segment_distance(centroid, a, b, &t);
      if (d < best) {
        best = d;
        nearest = a + t * (b - a);
      }
    }
    inward += normal.dot(centroid - nearest) < 0;
  }
  return inward;
}

QualityMetrics measure_quality(const QuadMesh& mesh, const PointCloud& cloud, const CellTree& cells,
                               const SkeletonGraph* skeleton) {
  QualityMetrics m;
  m.statistics = mesh_statistics(mesh);
  m.mesh_to_cloud = summarize_distances(mesh_to_cloud_distances(mesh, cloud));
  m.cloud_to_mesh = summarize_distances(cloud_to_mesh_distances(mesh, cloud));
  double sum = 0;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    device::mcq_vec3 q = device::mcq_make_vec3(float(p[0]), float(p[1]), float(p[2]));
    sum += device::mcq_vertex_error(cells.node_bounds.data(), cells.node_children.data(), cells.cell_offsets.data(),
                                    cells.points.data(), cells.cell_centroids.data(), cells.cell_normals.data(), q);
  }
  m.error_level = mesh.n_vertices() ? sum / mesh.n_vertices() : 0.0;
  if (skeleton) m.inward_faces = long(inward_faces(mesh, *skeleton));
  m.intersecting_face_pairs = intersecting_face_pairs(mesh).size();
  return m;
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

nlohmann::json to_json(const QualityMetrics& m) {
  auto summary = [](const DistanceSummary& d) { return nlohmann::json{{"mean", d.mean}, {"p95", d.p95}, {"max", d.max}}; };
  nlohmann::json j = {{"mesh", to_json(m.statistics)},
                      {"mesh_to_cloud", summary(m.mesh_to_cloud)},
                      {"cloud_to_mesh", summary(m.cloud_to_mesh)},
                      {"error_level", m.error_level},
                      {"intersecting_face_pairs", m.intersecting_face_pairs}};
  if (m.inward_faces >= 0) j["inward_faces"] = m.inward_faces;
  return j;
}

}  // namespace mcquad
