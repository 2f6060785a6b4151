#include "surfaces/surface_checks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>

#include "core/point_index.h"
#include "surfaces/cad_model.h"

namespace mcquad {
namespace {

//! A vertex's parameters in the surface of a face it belongs to.
Eigen::Vector2d parameter_in_face(const QuadMesh& mesh, const PatchLayout& layout, QuadMesh::FaceHandle f,
                                  QuadMesh::VertexHandle v) {
  int k = 0;
  for (auto corner : mesh.fv_range(f)) {
    if (corner == v) return layout.face_corner_parameters[size_t(f.idx())][size_t(k)];
    ++k;
  }
  return Eigen::Vector2d::Zero();
}

//! For every vertex, the number of edges to the nearest irregular vertex and
//! which one it is (multi-source breadth-first search; -1 when none).
void distances_to_irregular(const QuadMesh& mesh, std::vector<int>& distance, std::vector<int>& nearest) {
  distance.assign(mesh.n_vertices(), -1);
  nearest.assign(mesh.n_vertices(), -1);
  std::queue<QuadMesh::VertexHandle> queue;
  for (auto v : mesh.vertices()) {
    if (is_regular_vertex(mesh, v)) continue;
    distance[size_t(v.idx())] = 0;
    nearest[size_t(v.idx())] = v.idx();
    queue.push(v);
  }
  while (!queue.empty()) {
    auto v = queue.front();
    queue.pop();
    for (auto w : mesh.vv_range(v)) {
      if (distance[size_t(w.idx())] >= 0) continue;
      distance[size_t(w.idx())] = distance[size_t(v.idx())] + 1;
      nearest[size_t(w.idx())] = nearest[size_t(v.idx())];
      queue.push(w);
    }
  }
}

//! Whether two parameters are one point of the surface: equal, up to whole
//! periods in its periodic directions.
bool same_point(const BSplineSurface& surface, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  auto agrees = [](double x, double y, bool periodic, int period) {
    double difference = x - y;
    if (periodic) difference -= period * std::round(difference / period);
    return std::abs(difference) < 1e-9;
  };
  return agrees(a.x(), b.x(), surface.periodic_u, surface.spans_u()) &&
         agrees(a.y(), b.y(), surface.periodic_v, surface.spans_v());
}

double angle_degrees(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI;
}

//! Per vertex, the largest dihedral angle of the quad mesh at its edges.
std::vector<double> mesh_creases(const QuadMesh& mesh) {
  std::vector<Eigen::Vector3d> normals(mesh.n_faces());
  for (auto f : mesh.faces()) normals[size_t(f.idx())] = quad_vector_area(face_corners(mesh, f));
  std::vector<double> crease(mesh.n_vertices(), 0.0);
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    auto h = mesh.halfedge_handle(e, 0);
    double angle =
        angle_degrees(normals[size_t(mesh.face_handle(h).idx())], normals[size_t(mesh.opposite_face_handle(h).idx())]);
    for (auto v : {mesh.from_vertex_handle(h), mesh.to_vertex_handle(h)})
      crease[size_t(v.idx())] = std::max(crease[size_t(v.idx())], angle);
  }
  return crease;
}

//! The faces whose surface is farther from the cloud than the quad mesh (see
//! SurfaceChecks::off_cloud_tolerance), from the 9 samples per face.
void find_off_cloud_faces(const QuadMesh& mesh, const std::vector<int>& distance,
                          const std::vector<Eigen::Vector3d>& samples, const std::vector<double>& to_cloud,
                          const std::vector<double>& flat_to_cloud, double spacing, SurfaceChecks& checks) {
  // Distances to the nearest point jitter by about a point spacing between
  // two samples a spacing apart: that much more is noise, not a bulge. Where
  // the mesh itself is far from the cloud (not converged there), a curved
  // surface through its vertices is a little farther still: a tenth more is
  // the mesh's fault, not the surface's (the knot after 10 iterations has
  // faces 0.5-0.8 r off with surfaces up to 5 % farther).
  constexpr double kOffCloudRelativeSlack = 0.1;
  checks.off_cloud_slack = spacing;
  checks.off_cloud_tolerance = checks.mesh_to_cloud.p95;
  std::vector<OffCloudSurfaceSite> sites;
  for (size_t f = 0; f < mesh.n_faces(); ++f) {
    size_t worst = f * 9;
    double flat = 0;
    for (size_t k = f * 9; k < f * 9 + 9; ++k) {
      if (to_cloud[k] > to_cloud[worst]) worst = k;
      flat = std::max(flat, flat_to_cloud[k]);
    }
    double allowed = (1 + kOffCloudRelativeSlack) * std::max(checks.off_cloud_tolerance, flat) + spacing;
    if (to_cloud[worst] <= allowed) continue;
    int edges = -1;
    for (auto v : mesh.fv_range(QuadMesh::FaceHandle(int(f)))) {
      int d = distance[size_t(v.idx())];
      if (d >= 0 && (edges < 0 || d < edges)) edges = d;
    }
    sites.push_back({int(f), samples[worst], to_cloud[worst], allowed, edges});
  }
  checks.faces_off_cloud = sites.size();
  std::sort(sites.begin(), sites.end(), [](const OffCloudSurfaceSite& a, const OffCloudSurfaceSite& b) {
    return a.surface_distance - a.allowed_distance > b.surface_distance - b.allowed_distance;
  });
  if (sites.size() > SurfaceChecks::kMaxOffCloudSites) sites.resize(SurfaceChecks::kMaxOffCloudSites);
  checks.off_cloud_sites = std::move(sites);
}

void measure_distances(const QuadMesh& mesh, const std::vector<int>& distance, const PatchLayout& layout,
                       const std::vector<SurfaceEvaluator>& evaluators, const PointCloud* cloud,
                       SurfaceChecks& checks) {
  static constexpr double kAt[3] = {1.0 / 6.0, 0.5, 5.0 / 6.0};
  std::vector<Eigen::Vector3d> samples(mesh.n_faces() * 9), flat_samples(mesh.n_faces() * 9);
#pragma omp parallel for schedule(static)
  for (long fi = 0; fi < long(mesh.n_faces()); ++fi) {
    QuadMesh::FaceHandle f{static_cast<int>(fi)};
    const auto& corners = layout.face_corner_parameters[size_t(fi)];
    Eigen::Vector2d low = corners[0].cwiseMin(corners[1]).cwiseMin(corners[2]).cwiseMin(corners[3]);
    Eigen::Vector3d at[2][2];  // the face's corners by their offset from `low`
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      Eigen::Vector2d offset = corners[size_t(k++)] - low;
      at[int(std::lround(offset.x()))][int(std::lround(offset.y()))] = point_of(mesh, v);
    }
    const SurfaceEvaluator& surface = evaluators[size_t(layout.face_region[size_t(fi)])];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        double s = kAt[a], t = kAt[b];
        size_t index = size_t(fi) * 9 + size_t(a * 3 + b);
        samples[index] = surface.point(low.x() + s, low.y() + t);
        flat_samples[index] =
            (1 - s) * (1 - t) * at[0][0] + s * (1 - t) * at[1][0] + s * t * at[1][1] + (1 - s) * t * at[0][1];
      }
  }
  checks.samples = samples.size();
  PointCloud sample_cloud;
  sample_cloud.points.reserve(samples.size());
  for (const auto& p : samples) sample_cloud.points.emplace_back(p.cast<float>());
  checks.to_mesh = summarize_distances(cloud_to_mesh_distances(mesh, sample_cloud));
  if (!cloud || cloud->empty()) return;
  PointIndex<float> index(cloud->points);
  std::vector<double> to_cloud(samples.size()), flat_to_cloud(samples.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(samples.size()); ++i) {
    to_cloud[size_t(i)] = std::sqrt(double(index.nearest(samples[size_t(i)].cast<float>()).second));
    flat_to_cloud[size_t(i)] = std::sqrt(double(index.nearest(flat_samples[size_t(i)].cast<float>()).second));
  }
  checks.to_cloud = summarize_distances(to_cloud);
  checks.mesh_to_cloud = summarize_distances(flat_to_cloud);
  find_off_cloud_faces(mesh, distance, samples, to_cloud, flat_to_cloud, index.median_spacing(), checks);
}

void measure_seams(const QuadMesh& mesh, const std::vector<int>& distance, const std::vector<int>& nearest,
                   const PatchLayout& layout, const std::vector<BSplineSurface>& surfaces,
                   const std::vector<SurfaceEvaluator>& evaluators, SurfaceChecks& checks) {
  const std::vector<double> crease = mesh_creases(mesh);
  std::map<int, double> worst_at_site;
  for (auto e : mesh.edges()) {
    if (mesh.is_boundary(e)) continue;
    auto h = mesh.halfedge_handle(e, 0);
    auto f = mesh.face_handle(h), g = mesh.face_handle(mesh.opposite_halfedge_handle(h));
    auto a = mesh.from_vertex_handle(h), b = mesh.to_vertex_handle(h);
    int rf = layout.face_region[size_t(f.idx())], rg = layout.face_region[size_t(g.idx())];
    Eigen::Vector2d af = parameter_in_face(mesh, layout, f, a), bf = parameter_in_face(mesh, layout, f, b);
    Eigen::Vector2d ag = parameter_in_face(mesh, layout, g, a), bg = parameter_in_face(mesh, layout, g, b);
    if (rf == rg && same_point(surfaces[size_t(rf)], af, ag) && same_point(surfaces[size_t(rf)], bf, bg))
      continue;  // inside one surface
    checks.seam_edges += 1;
    double edge_gap = 0;
    for (int k = 0; k <= 4; ++k) {
      double t = k / 4.0;
      Eigen::Vector2d uf = (1 - t) * af + t * bf, ug = (1 - t) * ag + t * bg;
      const SurfaceEvaluator &sf = evaluators[size_t(rf)], &sg = evaluators[size_t(rg)];
      checks.max_position_gap =
          std::max(checks.max_position_gap, (sf.point(uf.x(), uf.y()) - sg.point(ug.x(), ug.y())).norm());
      edge_gap = std::max(edge_gap, angle_degrees(sf.normal(uf.x(), uf.y()), sg.normal(ug.x(), ug.y())));
    }
    checks.max_normal_gap_degrees = std::max(checks.max_normal_gap_degrees, edge_gap);
    int edge_distance = std::min(distance[size_t(a.idx())], distance[size_t(b.idx())]);
    bool smooth_mesh = std::max(crease[size_t(a.idx())], crease[size_t(b.idx())]) <= checks.smooth_mesh_degrees;
    bool far = edge_distance < 0 || edge_distance >= checks.far_edges;
    if (far && smooth_mesh)
      checks.max_normal_gap_away_from_irregular_degrees =
          std::max(checks.max_normal_gap_away_from_irregular_degrees, edge_gap);
    if (edge_gap <= checks.tangent_tolerance_degrees) {
      checks.seam_edges_within_tolerance += 1;
      continue;
    }
    if (smooth_mesh)
      checks.farthest_gap_from_irregular = std::max(checks.farthest_gap_from_irregular, edge_distance);
    else
      checks.gaps_at_mesh_creases += 1;
    int site =
        distance[size_t(a.idx())] <= distance[size_t(b.idx())] ? nearest[size_t(a.idx())] : nearest[size_t(b.idx())];
    if (site >= 0) worst_at_site[site] = std::max(worst_at_site[site], edge_gap);
  }
  for (const auto& [vertex, gap] : worst_at_site) {
    QuadMesh::VertexHandle v(vertex);
    checks.sites.push_back({vertex, int(mesh.valence(v)), point_of(mesh, v), gap, crease[size_t(vertex)]});
  }
  std::sort(checks.sites.begin(), checks.sites.end(), [](const NormalGapSite& x, const NormalGapSite& y) {
    return x.max_normal_gap_degrees > y.max_normal_gap_degrees;
  });
}

}  // namespace

SurfaceChecks check_surfaces(const QuadMesh& mesh, const PatchLayout& layout,
                             const std::vector<BSplineSurface>& surfaces, const PointCloud* cloud,
                             double tangent_tolerance_degrees) {
  SurfaceChecks checks;
  checks.tangent_tolerance_degrees = tangent_tolerance_degrees;
  checks.surfaces = surfaces.size();
  std::vector<SurfaceEvaluator> evaluators;
  evaluators.reserve(surfaces.size());
  for (const BSplineSurface& s : surfaces) {
    evaluators.emplace_back(s);
    checks.periodic_surfaces += s.periodic_u || s.periodic_v;
  }
  // Edges to the nearest irregular vertex, for the off-cloud faces and the seams.
  std::vector<int> distance, nearest;
  distances_to_irregular(mesh, distance, nearest);
  measure_distances(mesh, distance, layout, evaluators, cloud, checks);
  measure_seams(mesh, distance, nearest, layout, surfaces, evaluators, checks);
  return checks;
}

nlohmann::json to_json(const SurfaceChecks& c) {
  nlohmann::json sites = nlohmann::json::array();
  for (size_t k = 0; k < std::min<size_t>(c.sites.size(), 50); ++k) {
    const NormalGapSite& s = c.sites[k];
    sites.push_back({{"vertex", s.vertex},
                     {"valence", s.valence},
                     {"position", {s.position.x(), s.position.y(), s.position.z()}},
                     {"max_normal_gap_degrees", s.max_normal_gap_degrees},
                     {"mesh_crease_degrees", s.mesh_crease_degrees}});
  }
  nlohmann::json off_cloud = nlohmann::json::array();
  for (const OffCloudSurfaceSite& s : c.off_cloud_sites)
    off_cloud.push_back({{"face", s.face},
                         {"position", {s.position.x(), s.position.y(), s.position.z()}},
                         {"surface_distance", s.surface_distance},
                         {"allowed_distance", s.allowed_distance},
                         {"edges_from_irregular", s.edges_from_irregular}});
  return {{"surfaces", c.surfaces},
          {"periodic_surfaces", c.periodic_surfaces},
          {"samples", c.samples},
          {"distance_to_cloud", to_json(c.to_cloud)},
          {"quad_mesh_distance_to_cloud", to_json(c.mesh_to_cloud)},
          {"distance_to_quad_mesh", to_json(c.to_mesh)},
          {"off_cloud_tolerance", c.off_cloud_tolerance},
          {"off_cloud_slack", c.off_cloud_slack},
          {"faces_off_cloud", c.faces_off_cloud},
          {"off_cloud_sites", off_cloud},
          {"seam_edges", c.seam_edges},
          {"max_position_gap", c.max_position_gap},
          {"tangent_tolerance_degrees", c.tangent_tolerance_degrees},
          {"seam_edges_tangent_continuous", c.seam_edges_within_tolerance},
          {"max_normal_gap_degrees", c.max_normal_gap_degrees},
          {"smooth_mesh_degrees", c.smooth_mesh_degrees},
          {"max_normal_gap_degrees_smooth_mesh_two_or_more_edges_from_irregular",
           c.max_normal_gap_away_from_irregular_degrees},
          {"gaps_above_tolerance_on_smooth_mesh_within_edges_of_irregular", c.farthest_gap_from_irregular},
          {"gaps_above_tolerance_at_mesh_creases", c.gaps_at_mesh_creases},
          {"position_continuous_only_at", sites},
          {"position_continuous_only_sites", c.sites.size()}};
}

}  // namespace mcquad
