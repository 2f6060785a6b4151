#include "report/html_report.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <Eigen/Eigenvalues>

#include "core/errors.h"
#include "core/point_index.h"
#include "io/file_utils.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "metrics/mesh_metrics.h"
#include "pipeline/fit.h"
#include "embedded_report_page.h"  // generated from report_page.html (cmake/embed_sources.cmake)

namespace mcquad {
namespace {

//! Six significant digits: what a float holds, and half the bytes of %.17g.
double rounded(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  double scale = std::pow(10.0, 5 - std::floor(std::log10(std::fabs(x))));
  return std::round(x * scale) / scale;
}

nlohmann::json flat_points(const QuadMesh& mesh) {
  nlohmann::json out = nlohmann::json::array();
  for (auto v : mesh.vertices())
    for (int k = 0; k < 3; ++k) out.push_back(rounded(mesh.point(v)[k]));
  return out;
}

nlohmann::json faces_of(const QuadMesh& mesh) {
  nlohmann::json out = nlohmann::json::array();
  for (auto f : mesh.faces()) {
    nlohmann::json face = nlohmann::json::array();
    for (auto v : mesh.fv_range(f)) face.push_back(v.idx());
    out.push_back(face);
  }
  return out;
}

nlohmann::json mesh_json(const QuadMesh& mesh) { return {{"vertices", flat_points(mesh)}, {"faces", faces_of(mesh)}}; }

constexpr size_t kPlanePoints = 8;

//! Each vertex's distance to the cloud's local surface: the least-squares
//! plane of its kPlanePoints nearest points. The distance to the nearest
//! point alone speckles the picture with the point spacing.
std::vector<double> vertex_distances(const QuadMesh& mesh, const PointCloud& cloud) {
  PointIndex<float> index(cloud.points);
  std::vector<double> out(mesh.n_vertices());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(out.size()); ++i) {
    Eigen::Vector3d p = point_of(mesh, QuadMesh::VertexHandle(int(i)));
    std::vector<size_t> near = index.k_nearest(p.cast<float>(), kPlanePoints);
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (size_t j : near) centroid += cloud.points[j].cast<double>();
    centroid /= double(near.size());
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
    for (size_t j : near) {
      Eigen::Vector3d d = cloud.points[j].cast<double>() - centroid;
      scatter += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
    Eigen::Vector3d normal = solver.eigenvectors().col(0);  // the smallest eigenvalue's
    out[size_t(i)] = near.size() >= 3 ? std::fabs((p - centroid).dot(normal)) : (p - centroid).norm();
  }
  return out;
}

//! Scalars of a JSON tree as "a.b.c": value rows for the page's tables.
void flatten(const nlohmann::json& j, const std::string& prefix, nlohmann::json& out) {
  if (j.is_object()) {
    for (const auto& [key, value] : j.items())
      flatten(value, prefix.empty() ? key : std::string(prefix).append(".").append(key), out);
  } else if (!j.is_array()) {
    out[prefix] = j;
  }
}

nlohmann::json table(const nlohmann::json& report, const char* section) {
  nlohmann::json out = nlohmann::json::object();
  if (report.contains(section)) flatten(report[section], "", out);
  return out;
}

//! Crossing sites and every failed check's sites, for the red marks.
nlohmann::json failed_sites(const nlohmann::json& report) {
  nlohmann::json out = nlohmann::json::array();
  if (report.contains("verdict"))
    for (const auto& check : report["verdict"]["checks"])
      if (!check["passed"].get<bool>())
        for (const auto& p : check["sites"]) out.push_back(p);
  return out;
}

nlohmann::json page_data(const HtmlReportInput& in) {
  const nlohmann::json& report = *in.report;
  nlohmann::json data;
  data["title"] = in.title;
  size_t stride = std::max<size_t>(1, (in.cloud->size() + kHtmlReportMaxCloudPoints - 1) / kHtmlReportMaxCloudPoints);
  nlohmann::json cloud = nlohmann::json::array();
  for (size_t i = 0; i < in.cloud->size(); i += stride)
    for (int k = 0; k < 3; ++k) cloud.push_back(rounded(in.cloud->points[i][k]));
  data["cloud"] = cloud;
  data["cloud_count"] = in.cloud->size();
  data["cloud_shown"] = cloud.size() / 3;
  if (in.skeleton) {
    nlohmann::json nodes = nlohmann::json::array(), edges = nlohmann::json::array();
    for (const auto& p : in.skeleton->nodes)
      for (int k = 0; k < 3; ++k) nodes.push_back(rounded(p[k]));
    for (const auto& e : in.skeleton->edges) edges.push_back(e[0]), edges.push_back(e[1]);
    data["skeleton"] = {{"nodes", nodes}, {"edges", edges}};
  }
  data["final"] = mesh_json(*in.final_mesh);
  nlohmann::json distance = nlohmann::json::array();
  for (double d : vertex_distances(*in.final_mesh, *in.cloud)) distance.push_back(rounded(d));
  data["final"]["distance"] = distance;
  data["initial"] = in.initial_mesh ? mesh_json(*in.initial_mesh) : nlohmann::json();
  data["irregular"] = irregular_vertices(*in.final_mesh);
  // Colours run to 5 % of the median radius (the verdict's coverage bound),
  // so red means "farther than a good fit would be".
  double radius = report.contains("parameters") ? report["parameters"].value("median_radius", 0.0) : 0.0;
  data["distance_scale"] = 0.05 * radius;
  data["distance_scale_meaning"] = "5 % of the median local radius; distance to the plane of the 8 nearest points";
  data["verdict"] = report.contains("verdict") ? report["verdict"] : nlohmann::json();
  data["failed_sites"] = failed_sites(report);
  data["initial_error_level"] =
      report.contains("evolution") ? report["evolution"]["initial_error_level"] : nlohmann::json();
  nlohmann::json levels = nlohmann::json::array();
  if (report.contains("evolution"))
    for (const auto& it : report["evolution"]["iterations"]) levels.push_back(it["error_level"]);
  data["error_levels"] = levels;
  nlohmann::json metrics = table(report, "metrics");
  metrics.erase("crossing_sites");
  data["tables"] = {
      {"metrics", metrics}, {"parameters", table(report, "parameters")}, {"timings", table(report, "timings_seconds")}};
  return data;
}

//! Replaces the one `marker` in `page` by `text`.
void fill(std::string& page, const std::string& marker, const std::string& text) {
  size_t at = page.find(marker);
  if (at == std::string::npos) throw std::logic_error("report page template lacks " + marker);
  page.replace(at, marker.size(), text);
}

const char* const kThreeJsFiles[] = {"three.min.js", "examples/js/controls/OrbitControls.js"};

std::string read_three_js() {
  check_three_js();
  std::string sources;
  for (const char* file : kThreeJsFiles)
    sources += read_file((std::filesystem::path(three_js_directory()) / file).string()) + "\n";
  return sources;
}

//! JSON inside a <script> element: "</" would end the element early.
std::string script_safe(std::string text) {
  for (size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3) text.replace(at, 2, "<\\/");
  return text;
}

InitialMeshOptions initial_options_from(const nlohmann::json& p) {
  InitialMeshOptions o;
  o.start_fraction = p.value("start_fraction", o.start_fraction);
  o.block_fraction = p.value("block_fraction", o.start_fraction);  // reports before 2026-12-04: the start fraction
  o.resolution = p.value("resolution", o.resolution);
  o.target_vertices = p.value("target_vertices", o.target_vertices);
  o.ends = end_mode_from_name(p.value("ends", std::string("auto")), "ends");
  o.junction_inflation = p.value("junction_inflation", o.junction_inflation);
  if (p.contains("min_junction_angle_degrees"))
    o.min_junction_angle = p["min_junction_angle_degrees"].get<double>() * M_PI / 180.0;
  return o;
}

}  // namespace

void check_three_js() {
  for (const char* file : kThreeJsFiles) {
    std::error_code ec;
    std::filesystem::path path = std::filesystem::path(three_js_directory()) / file;
    if (!std::filesystem::is_regular_file(path, ec))
      throw OutputError("cannot write an HTML report: " + path.string() +
                        " is missing (install Debian's libjs-three, or set MCQUAD_THREE_JS_DIR)");
  }
}

std::string three_js_directory() {
  const char* env = std::getenv("MCQUAD_THREE_JS_DIR");
  return env && *env ? env : "/usr/share/javascript/three";
}

void write_html_report(const std::string& path, const HtmlReportInput& input) {
  std::string page = embedded::report_page_html;
  fill(page, "/*MCQUAD_THREE*/", read_three_js());
  fill(page, "/*MCQUAD_DATA*/", script_safe(page_data(input).dump()));
  write_text_atomically(path, page);
}

void write_html_report_from_json(const std::string& report_path, const std::string& mesh_path,
                                 const std::string& html_path) {
  nlohmann::json report;
  try {
    report = nlohmann::json::parse(read_file(report_path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(report_path + ": not valid JSON: " + e.what());
  }
  auto text_at = [&](const char* section, const char* key) {
    if (!report.contains(section) || !report[section].contains(key) || !report[section][key].is_string())
      throw InputError(report_path + ": not a fit report (no " + section + "." + key + ")");
    return report[section][key].get<std::string>();
  };
  std::string points = text_at("inputs", "points"), skeleton_path = text_at("inputs", "skeleton");
  std::string mesh_file = mesh_path.empty() ? text_at("outputs", "mesh") : mesh_path;
  if (!report.contains("parameters")) throw InputError(report_path + ": not a fit report (no parameters)");
  QuadMesh final_mesh = read_mesh(mesh_file);
  PointCloud cloud = read_point_cloud(points);
  SkeletonData skeleton = read_skeleton(skeleton_path);
  FitOptions init;
  init.initial = initial_options_from(report["parameters"]);
  init.evolve = false;
  init.measure = false;
  // From the cloud and skeleton already read (a copy: the fit sorts its
  // cloud), not from the files a second time; the same mesh either way.
  FitResult initial = run_fit(FitInput{cloud, skeleton, points, skeleton_path}, init);
  HtmlReportInput input;
  input.report = &report;
  input.final_mesh = &final_mesh;
  input.initial_mesh = &initial.mesh;
  input.cloud = &cloud;
  input.skeleton = &skeleton;
  input.title = std::filesystem::path(mesh_file).filename().string();
  write_html_report(html_path, input);
}

}  // namespace mcquad
