#include "pipeline/surfaces.h"

#include <chrono>

#include "io/file_utils.h"
#include "io/mesh_io.h"
#include "surfaces/surface_model.h"

namespace mcquad {
namespace {

double diagonal(const QuadMesh& mesh) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    Eigen::Vector3d q(p[0], p[1], p[2]);
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  return mesh.n_vertices() > 0 ? (high - low).norm() : 1.0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

nlohmann::json to_json(const SurfaceReport& r) {
  nlohmann::json report;
  report["layout"] = {{"regions", r.regions},
                      {"irregular_vertices", r.irregular_vertices},
                      {"separatrix_edges", r.separatrix_edges},
                      {"single_face_fallbacks", r.single_face_fallbacks}};
  report["fit_seconds"] = r.fit_seconds;
  if (r.cad_file)
    report["cad_file"] = {{"path", r.cad_file->path},
                          {"units", r.cad_file->units},
                          {"faces_written", r.cad_file->faces_written},
                          {"faces_read_back", r.cad_file->read_back.faces},
                          {"bspline_faces_read_back", r.cad_file->read_back.bspline_faces},
                          {"free_edges_read_back", r.cad_file->read_back.free_edges},
                          {"shells_read_back", r.cad_file->read_back.shells},
                          {"valid_read_back", r.cad_file->read_back.valid},
                          {"seconds", r.cad_file->seconds}};
  report["checks"] = to_json(r.checks);
  report["checks_seconds"] = r.checks_seconds;
  return report;
}

SurfaceReport export_surfaces(const QuadMesh& mesh, const PointCloud* cloud, const SurfaceOutputs& outputs,
                              VerdictCheck* off_cloud_check) {
  check_cad_unit(outputs.units);
  auto start = std::chrono::steady_clock::now();
  SurfaceModel model = build_surface_model(mesh);
  const PatchLayout& layout = model.layout;
  SurfaceReport report;
  report.regions = layout.regions.size();
  report.irregular_vertices = layout.irregular_vertices;
  report.separatrix_edges = layout.separatrix_edges;
  report.single_face_fallbacks = layout.single_face_fallbacks;
  report.fit_seconds = seconds_since(start);

  if (!outputs.cad_path.empty()) {
    start = std::chrono::steady_clock::now();
    // Seams meet to rounding error (both sides interpolate the same curve);
    // the sewing tolerance only has to absorb that.
    CadModel cad(model.surfaces, 1e-7 * diagonal(mesh));
    cad.write(outputs.cad_path, outputs.units);
    report.cad_file =
        CadFileReport{outputs.cad_path, outputs.units, cad.face_count(), read_cad_file(outputs.cad_path), 0.0};
    report.cad_file->seconds = seconds_since(start);
  }
  if (!outputs.control_nets_path.empty()) write_mesh(outputs.control_nets_path, control_net_mesh(model.surfaces));

  start = std::chrono::steady_clock::now();
  report.checks = check_surfaces(mesh, layout, model.surfaces, cloud, outputs.tangent_tolerance_degrees);
  const SurfaceChecks& checks = report.checks;
  if (off_cloud_check && cloud && !cloud->empty()) {
    *off_cloud_check =
        make_check("surfaces_off_cloud",
                   "faces whose B-spline surface is farther from the cloud than the quad mesh (more than "
                   "1.1 x the mesh's 95th percentile or the face's own distance, plus one point spacing)",
                   double(checks.faces_off_cloud), VerdictCheck::Bound::kAtMost, 0);
    for (const OffCloudSurfaceSite& site : checks.off_cloud_sites) off_cloud_check->sites.push_back(site.position);
  }
  report.checks_seconds = seconds_since(start);
  return report;
}

}  // namespace mcquad
