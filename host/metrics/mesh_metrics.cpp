#include "metrics/mesh_metrics.h"

#include <numeric>

#include <set>

#include "core/point_index.h"
#include "core/shared_math.h"
#include "mesh/face_intersections.h"
#include "skeleton/bone_assignment.h"

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

size_t inward_faces(const QuadMesh& mesh, const SkeletonGraph& skeleton) {
  return inward_face_indices(mesh, skeleton).size();
}

std::vector<int> inward_face_indices(const QuadMesh& mesh, const SkeletonGraph& skeleton) {
  std::vector<int> inward;
  std::vector<double> distance(skeleton.edges.size());
  std::vector<Eigen::Vector3d> nearest(skeleton.edges.size());
  for (auto f : mesh.faces()) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> corners;
    for (auto v : mesh.fv_range(f)) {
      const auto& p = mesh.point(v);
      corners.emplace_back(p[0], p[1], p[2]);
      centroid += corners.back();
    }
    centroid /= double(corners.size());
    Eigen::Vector3d normal = face_vector_area(mesh, f);
    double closest = INFINITY;
    for (size_t b = 0; b < skeleton.edges.size(); ++b) {
      double t;
      const auto& a = skeleton.positions[skeleton.edges[b][0]];
      const auto& c = skeleton.positions[skeleton.edges[b][1]];
      distance[b] = segment_distance(centroid, a, c, &t);
      nearest[b] = a + t * (c - a);
      closest = std::min(closest, distance[b]);
    }
    // "Out of the tube" is the gradient of a smooth minimum of the distances
    // to the bones: away from the nearest bone along a tube, and out of the
    // crotch where two bones are about equally near (where the nearest bone
    // alone would flip between them).
    double scale = std::max(0.3 * closest, 1e-12);
    Eigen::Vector3d outward = Eigen::Vector3d::Zero();
    for (size_t b = 0; b < skeleton.edges.size(); ++b) {
      if (distance[b] > closest + 8 * scale || distance[b] <= 0) continue;
      outward += std::exp(-(distance[b] - closest) / scale) * (centroid - nearest[b]) / distance[b];
    }
    if (normal.dot(outward) < 0) inward.push_back(f.idx());
  }
  return inward;
}

double winding_number(const QuadMesh& mesh, const Eigen::Vector3d& p) {
  // Van Oosterom-Strackee solid angle of every triangle.
  double total = 0;
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> c;
    for (auto v : mesh.fv_range(f)) c.emplace_back(point_of(mesh, v) - p);
    for (size_t k = 1; k + 1 < c.size(); ++k) {
      const Eigen::Vector3d &a = c[0], &b = c[k], &d = c[k + 1];
      double la = a.norm(), lb = b.norm(), ld = d.norm();
      double numerator = a.dot(b.cross(d));
      double denominator = la * lb * ld + a.dot(b) * ld + b.dot(d) * la + d.dot(a) * lb;
      total += 2.0 * std::atan2(numerator, denominator);
    }
  }
  return total / (4.0 * M_PI);
}

namespace {

//! Indices of the `count` largest values, largest first.
std::vector<size_t> largest_first(const std::vector<double>& values, size_t count) {
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), size_t(0));
  count = std::min(count, order.size());
  std::partial_sort(order.begin(), order.begin() + long(count), order.end(),
                    [&](size_t a, size_t b) { return values[a] > values[b]; });
  order.resize(count);
  return order;
}

}  // namespace

std::vector<int> faces_against_normals(const QuadMesh& mesh, const OrientedSample& oriented) {
  PointIndex<float> index(oriented.points);
  std::vector<char> against(mesh.n_faces(), 0);
#pragma omp parallel for schedule(static)
  for (long f = 0; f < long(mesh.n_faces()); ++f) {
    Eigen::Vector3d normal = face_vector_area(mesh, mesh.face_handle(int(f)));
    long nearest = index.nearest(face_centroid(mesh, int(f)).cast<float>()).first;
    if (nearest >= 0) against[size_t(f)] = normal.dot(oriented.normals[size_t(nearest)].cast<double>()) < 0;
  }
  std::vector<int> faces;
  for (size_t f = 0; f < against.size(); ++f)
    if (against[f]) faces.push_back(int(f));
  return faces;
}

double area_fraction(const QuadMesh& mesh, const std::vector<int>& faces) {
  auto area = [&](QuadMesh::FaceHandle f) { return 0.5 * face_vector_area(mesh, f).norm(); };
  double total = 0, part = 0;
  for (auto f : mesh.faces()) total += area(f);
  for (int f : faces) part += area(mesh.face_handle(f));
  return total > 0 ? part / total : 0.0;
}

QualityMetrics measure_quality(const QuadMesh& mesh, const PointCloud& cloud, const CellTree& cells,
                               const SkeletonGraph* skeleton, const OrientedSample* oriented) {
  QualityMetrics m;
  m.statistics = mesh_statistics(mesh);
  std::vector<double> off_cloud = mesh_to_cloud_distances(mesh, cells);
  for (size_t v : largest_first(off_cloud, QualityMetrics::kMaxSites))
    m.off_cloud_sites.push_back(point_of(mesh, QuadMesh::VertexHandle(int(v))));
  m.mesh_to_cloud = summarize_distances(std::move(off_cloud));
  // A million points pin the percentiles down; more only cost time.
  constexpr size_t kMaxCloudPoints = 1000000;
  std::vector<double> uncovered = cloud_to_mesh_distances(mesh, cloud, kMaxCloudPoints);
  size_t stride = cloud_sample_stride(cloud.size(), kMaxCloudPoints);
  for (size_t k : largest_first(uncovered, QualityMetrics::kMaxSites))
    m.uncovered_sites.emplace_back(cloud.points[k * stride].cast<double>());
  m.cloud_to_mesh = summarize_distances(std::move(uncovered));
  std::vector<float> positions;
  positions.reserve(3 * mesh.n_vertices());
  for (auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) positions.push_back(float(mesh.point(v)[k]));
  m.error_level = mean_vertex_error(cells, positions);
  m.cloud_spacing = cells.point_spacing;
  if ((oriented && !oriented->empty()) || skeleton) {
    bool by_normals = oriented && !oriented->empty();
    std::vector<int> inward =
        by_normals ? faces_against_normals(mesh, *oriented) : inward_face_indices(mesh, *skeleton);
    m.inward_reference = by_normals ? "scan normals" : "skeleton";
    m.inward_faces = long(inward.size());
    m.inward_area_fraction = area_fraction(mesh, inward);
    std::vector<double> areas;
    areas.reserve(inward.size());
    for (int f : inward) areas.push_back(face_vector_area(mesh, mesh.face_handle(f)).norm());
    for (size_t k : largest_first(areas, QualityMetrics::kMaxSites))
      m.inward_sites.push_back(face_centroid(mesh, inward[k]));
  }
  std::vector<Eigen::Vector3d> loops = boundary_loop_centres(mesh);
  if (loops.size() > QualityMetrics::kMaxSites) loops.resize(QualityMetrics::kMaxSites);
  m.boundary_sites = std::move(loops);
  for (auto e : mesh.edges()) {
    if (!is_folded(mesh, e)) continue;
    if (++m.folded_edges > QualityMetrics::kMaxSites) continue;
    auto h = mesh.halfedge_handle(e, 0);
    m.fold_sites.emplace_back(0.5 *
                              (point_of(mesh, mesh.from_vertex_handle(h)) + point_of(mesh, mesh.to_vertex_handle(h))));
  }
  std::vector<std::pair<int, int>> crossing = intersecting_face_pairs(mesh);
  m.intersecting_face_pairs = crossing.size();
  for (size_t k = 0; k < crossing.size() && k < QualityMetrics::kMaxCrossingSites; ++k)
    m.crossing_sites.emplace_back(0.5 *
                                  (face_centroid(mesh, crossing[k].first) + face_centroid(mesh, crossing[k].second)));
  m.quad_shape = measure_quad_shape(mesh);
  std::vector<double> badness;  // minus the scaled Jacobian, so that the worst come first
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> corners = face_corners(mesh, f);
    badness.push_back(corners.size() == 4 ? -scaled_jacobian(corners.data()) : 0.0);
  }
  for (size_t f : largest_first(badness, QualityMetrics::kMaxSites))
    if (badness[f] >= 0) m.worst_quad_sites.push_back(face_centroid(mesh, int(f)));
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
  nlohmann::json j = {{"mesh", to_json(m.statistics)},
                      {"mesh_to_cloud", to_json(m.mesh_to_cloud)},
                      {"cloud_to_mesh", to_json(m.cloud_to_mesh)},
                      {"error_level", m.error_level},
                      {"cloud_spacing", m.cloud_spacing},
                      {"intersecting_face_pairs", m.intersecting_face_pairs},
                      {"folded_edges", m.folded_edges},
                      {"quad_shape", to_json(m.quad_shape)}};
  if (m.inward_faces >= 0) {
    j["inward_faces"] = m.inward_faces;
    j["inward_area_fraction"] = m.inward_area_fraction;
    j["inward_measured_against"] = m.inward_reference;
  }
  auto sites = [](const std::vector<Eigen::Vector3d>& points) {
    nlohmann::json out = nlohmann::json::array();
    for (const Eigen::Vector3d& p : points) out.push_back({p.x(), p.y(), p.z()});
    return out;
  };
  j["crossing_sites"] = sites(m.crossing_sites);
  j["worst_sites"] = {{"folds", sites(m.fold_sites)},
                      {"worst_quads", sites(m.worst_quad_sites)},
                      {"inward_faces", sites(m.inward_sites)},
                      {"open_ends", sites(m.boundary_sites)},
                      {"uncovered_cloud", sites(m.uncovered_sites)},
                      {"farthest_vertices", sites(m.off_cloud_sites)}};
  return j;
}

}  // namespace mcquad
