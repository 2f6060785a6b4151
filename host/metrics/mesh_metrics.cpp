#include "metrics/mesh_metrics.h"

#include <numeric>

#include "mesh/face_intersections.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {
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

QualityMetrics measure_quality(const QuadMesh& mesh, const PointCloud& cloud, const CellTree& cells,
                               const SkeletonGraph* skeleton, const ScanOrientation* scan) {
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
  m.error_level = mean_vertex_error(cells, mesh_positions(mesh));
  m.cloud_spacing = cells.point_spacing;
  if ((scan && !scan->empty()) || skeleton) {
    bool by_normals = scan && !scan->empty();
    std::vector<int> inward = by_normals ? scan->inward_faces(mesh) : inward_face_indices(mesh, *skeleton);
    m.inward_reference = by_normals ? "scan normals" : "skeleton";
    m.inward_faces = long(inward.size());
    m.inward_area_fraction = by_normals ? scan->inward_area_fraction(mesh, inward) : area_fraction(mesh, inward);
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
