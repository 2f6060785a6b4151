// The `mcquad` command: subcommands over the library's pipeline stages.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "core/point_text.h"
#include "core/errors.h"
#include "core/progress.h"
#include "generate/shapes.h"
#include "generate/true_surface_distance.h"
#include "io/file_utils.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"
#include "metrics/mesh_metrics.h"
#include "pipeline/fit.h"
#include "pipeline/measure.h"
#include "pipeline/skeleton_extraction.h"
#include "pipeline/surfaces.h"
#include "report/html_report.h"
#ifdef MCQUAD_WITH_OPENCL
#include "opencl/device_selection.h"
#endif

namespace {

using namespace mcquad;

//! Fails early, before hours of work, when an output cannot be written.
void check_output_path(const std::string& path, const std::vector<std::string>& extensions) {
  std::string ext = file_extension(path);
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
    std::string accepted;
    for (const auto& e : extensions) accepted += (accepted.empty() ? "." : ", .") + e;
    throw OutputError(path + ": unknown extension '." + ext + "' (expected " + accepted + ")");
  }
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    throw OutputError(path + ": cannot write: directory " + dir.string() + " does not exist");
}

void print_surface_summary(const SurfaceReport& report, bool with_cloud);

// Function-local statics: built on first use, where an allocation failure can
// be caught, not before main.
const std::vector<std::string>& mesh_extensions() {
  static const std::vector<std::string> kExtensions = {"obj", "off", "ply", "om", "stl", "stla"};
  return kExtensions;
}
const std::vector<std::string>& cad_extensions() {
  static const std::vector<std::string> kExtensions = {"step", "stp", "iges", "igs"};
  return kExtensions;
}

//! The failed checks on stderr, the verdict on stdout; the exit code.
int report_verdict(const Verdict& verdict, bool strict) {
  for (const std::string& line : verdict_warnings(verdict)) warn(line);
  std::printf("verdict: %s (%zu of %zu checks passed)\n", verdict.passed ? "pass" : "FAIL",
              verdict.checks.size() - verdict.failures().size(), verdict.checks.size());
  return strict && !verdict.passed ? kExitVerdict : kExitOk;
}

//! The CLI11 check for a ranged fit option, from the library's one table.
CLI::Range range(const char* name) {
  const OptionRange& r = fit_option_range(name);
  return CLI::Range(r.low, r.high);
}

//! An option taking one of the words of `words` (pipeline/fit_options.h):
//! CLI11 turns the word into its value (as the number CLI11 reads enums
//! and bools from); anything else is a usage error naming the words.
template <typename Value>
CLI::Option* add_word_option(CLI::App* app, const std::string& name, Value& value, const OptionWords<Value>& words,
                             const std::string& help) {
  std::string accepted;
  for (const auto& entry : words) accepted += std::string(accepted.empty() ? "" : ", ") + entry.word;
  CLI::Validator to_value(
      [&words, accepted](std::string& input) -> std::string {
        for (const auto& [word, v] : words)
          if (input == word) {
            input = std::to_string(static_cast<long>(v));
            return "";
          }
        return "'" + input + "' is not one of " + accepted;
      },
      "");
  return app->add_option(name, value, help)->transform(to_value)->type_name("WORD")->default_str(word_of(value, words));
}

struct FitCommand {
  std::string points, skeleton, output, report, html;
  FitOptions options;
  double alpha_degrees = 10.0;
  double junction_degrees = 75.0;
  bool strict = false;

  void add_options(CLI::App* app, bool evolution) {
    app->add_option("POINTS", points, "point cloud (.ply, .xyz, .txt, .csv, .obj, .off)")->required();
    app->add_option(
        "SKELETON", skeleton,
        "skeleton (.obj with v/l lines, or CGAL polylines .cgal/.polylines/.txt); none: extracted from the cloud "
        "(as by mcquad skeleton)");
    app->add_option("-o,--output", output,
                    "output mesh (.obj, .off, .ply, .om; .stl binary or .stla ASCII, triangulated)")
        ->required();
    app->add_option("--report", report, "write a JSON report here");
    if (evolution)
      app->add_option("--html", html,
                      "write a self-contained HTML report here (the meshes, cloud and verdict to turn around)");
    auto& init = options.initial;
    add_word_option(app, "--ends", init.ends, end_mode_words(), "ends: auto (decided from the cloud), open or capped");
    app->add_option("--start-fraction", init.start_fraction,
                    "initial mesh radius as a fraction of the local cloud radius")
        ->check(range("start_fraction"))
        ->capture_default_str();
    app->add_option("--block-fraction", init.block_fraction,
                    "robust mode: junction blocks' radius as a fraction of the local cloud radius (at least the "
                    "start fraction)")
        ->check(range("block_fraction"))
        ->capture_default_str();
    app->add_option("--resolution", init.resolution,
                    "target edge length of the refined mesh (0 = 16 vertices around a tube)")
        ->check(range("resolution"))
        ->capture_default_str();
    app->add_option("--target-vertices", init.target_vertices, "refine until at least this many vertices (0 = off)")
        ->capture_default_str();
    app->add_option("--min-junction-angle", junction_degrees,
                    "junctions whose bones fork more acutely move to where the cloud's tubes part (0 = never)")
        ->check(range("min_junction_angle"))
        ->capture_default_str();
    app->add_option("--junction-inflation", init.junction_inflation,
                    "robust mode: move the mesh round each junction this fraction of the way to the cloud along rays "
                    "from its node (0 = off)")
        ->check(range("junction_inflation"))
        ->capture_default_str();
    add_word_option(app, "--limb-ports", init.limb_ports, on_off_words(),
                    "robust mode: a limb over 2.5 times thinner than its junction block's face starts from a face "
                    "of its own size inset in it, at the trunk's wall (on, off; docs/HARD_CASES.md, \"Thin limbs "
                    "start at their trunk's wall\")");
    app->add_option("--write-skeleton", options.construction_skeleton, "write the skeleton the mesh is built on (OBJ)");
    if (!evolution) {
      add_word_option(app, "--stage", init.stage, construction_stage_words(),
                      "stop after: blocks, extruded or refined");
      return;
    }
    app->add_flag("--strict", strict, "exit with code 7 (after writing the outputs) when a check of the verdict fails");
    auto& e = options.evolution;
    add_word_option(app, "--backend", options.backend, backend_words(),
                    "auto (OpenCL if a device exists), serial or opencl");
    app->add_option("--device", options.device,
                    "OpenCL device index or name (default: $MCQUAD_DEVICE, else first GPU, else first device)");
    add_word_option(app, "--mode", e.mode, evolution_mode_words(),
                    "robust (improvements over the paper, docs/DESIGN.md) or paper (the paper's step exactly)");
    app->add_option("--relaxation", e.relaxation,
                    "robust mode: tangential relaxation weight before each step (0 = off)")
        ->check(range("relaxation"))
        ->capture_default_str();
    add_word_option(app, "--projection", e.mean_projection, projection_words(),
                    "robust mode: a cell's distance along a ray from its samples: mean, or min (the paper's)");
    add_word_option(app, "--fill-holes", e.fill_holes, on_off_words(),
                    "robust mode: vertices that find no cell take their neighbours' offset (on, off)");
    add_word_option(app, "--nearest-plane", e.nearest_plane, on_off_words(),
                    "robust mode: vertices that find no cell with the cloud within epsilon move along the scan's "
                    "normal at their nearest point to its level (on, off)");
    add_word_option(
        app, "--crossing-guard", e.crossing_guard, on_off_words(),
        "robust mode: shorten moves that make faces cross or fold, turn over or lose shape, after each step (on, off)");
    app->add_option("--held-back-relaxation", e.held_back_relaxation,
                    "robust mode: tangential relaxation weight for the vertices the crossing guard held back (0 = off)")
        ->check(range("held_back_relaxation"))
        ->capture_default_str();
    add_word_option(app, "--own-cells", e.own_cells, on_off_words(),
                    "robust mode: a vertex sees only the cells of the bones near its own (on, off)");
    add_word_option(app, "--local-epsilon", e.local_epsilon, on_off_words(),
                    "robust mode: epsilon and the ray reach scale with the local radius (on, off)");
    add_word_option(app, "--coarse-to-fine", e.coarse_to_fine, on_off_words(),
                    "robust mode, finer than the default resolution: evolve the default resolution's mesh first, then "
                    "refine it and evolve again (on, off)");
    add_word_option(app, "--refine-uncovered", e.refine_uncovered, on_off_words(),
                    "robust mode, at the default resolution: where the fit leaves the cloud uncovered (the verdict's "
                    "bound), refine the fitted mesh once and evolve again (on, off)");
    app->add_option("--hit-band", e.hit_band,
                    "robust mode: a ray averages every cell within this fraction of epsilon of its first hit (0 = the "
                    "first cell only)")
        ->check(range("hit_band"))
        ->capture_default_str();
    add_word_option(app, "--facing-cells", e.facing_cells, on_off_words(),
                    "robust mode, on a scan with normals: rays pass through cells whose normals face away from the "
                    "vertex (on, off)");
    app->add_option(
           "--min-facing", e.min_facing,
           "robust mode: the least cosine of the angle between a cell's scan normal and the vertex normal for a "
           "ray to hit the cell (-1 to 0.95)")
        ->check(range("min_facing"))
        ->capture_default_str();
    add_word_option(app, "--curvature-correction", e.curvature_correction, on_off_words(),
                    "robust mode: correct each sample's projection by the mesh's curvature, so that vertices settle "
                    "on a curved surface, not inside it (on, off)");
    app->add_option("--turned-face-rounds", e.turned_face_rounds,
                    "robust mode, on a scan with normals: at most this many rounds of smoothing the faces turned "
                    "against the scan's normals after the evolution (0 = off)")
        ->check(range("turned_face_rounds"))
        ->capture_default_str();
    add_word_option(app, "--push-deep", e.push_deep, on_off_words(),
                    "robust mode, on a scan with normals, with the smoothing of turned faces: push vertices left deep "
                    "below the scan out first; the pushed fit is kept where it turns no more area against the scan "
                    "(on, off)");
    add_word_option(app, "--reach-uncovered", e.reach_uncovered, on_off_words(),
                    "robust mode: after the evolution, cloud points it left more than a sixth of epsilon from the "
                    "mesh pull it; the fit so reached is kept where its cloud -> mesh p95 is lower and, on a scan "
                    "with normals, the area it turns against the scan stays within the verdict's bound or grows not "
                    "at all (on, off)");
    app->add_option("--iterations", e.iterations, "maximal number of iterations")->capture_default_str();
    app->add_option("--tolerance", e.tolerance,
                    "stop when the error level improves by less than this fraction (0 = never)")
        ->check(range("tolerance"))
        ->capture_default_str();
    app->add_option("--seed", e.seed, "random seed")->capture_default_str();
    app->add_option("--cones", e.cones, "c: number of cones")->check(range("cones"))->capture_default_str();
    app->add_option("--generators", e.generators, "r: rays per cone")
        ->check(range("generators"))
        ->capture_default_str();
    app->add_option("--alpha-max", alpha_degrees, "maximal cone half angle, degrees")
        ->check(range("alpha_max"))
        ->capture_default_str();
    app->add_option("--samples", e.samples, "m: random samples per hit cell")
        ->check(range("samples"))
        ->capture_default_str();
    app->add_option("--epsilon", e.epsilon, "feasibility bound and ray reach (0 = 0.6 x median local radius)")
        ->check(range("epsilon"))
        ->capture_default_str();
    app->add_option("--leaf-size", options.leaf_size,
                    "maximal points per cell (0 = 6, growing in proportion above 2 million points)")
        ->check(range("leaf_size"))
        ->capture_default_str();
    app->add_option("--snapshots", options.snapshots_directory,
                    "write the mesh after every iteration into this directory");
    app->add_option("--surfaces", options.surfaces.cad_path,
                    "also write the final mesh as B-spline surfaces (.step, .stp, .iges, .igs)");
    app->add_option("--control-nets", options.surfaces.control_nets_path,
                    "also write the surfaces' control nets (.obj, .off, .ply, .om)");
    app->add_option("--units", options.surfaces.units,
                    "the length unit the CAD file declares; the coordinates are written as they are")
        ->check(CLI::IsMember({"mm", "cm", "m", "um", "in", "ft"}))
        ->capture_default_str();
  }

  int run(bool evolution) {
    check_output_path(output, mesh_extensions());
    if (!report.empty()) check_output_path(report, {"json"});
    if (!html.empty()) check_output_path(html, {"html"});
    if (!html.empty()) check_three_js();
    if (!options.surfaces.cad_path.empty()) check_output_path(options.surfaces.cad_path, cad_extensions());
    if (!options.surfaces.control_nets_path.empty())
      check_output_path(options.surfaces.control_nets_path, mesh_extensions());
    options.evolve = evolution;
    options.evolution.alpha_max = alpha_degrees * M_PI / 180.0;
    options.initial.min_junction_angle = junction_degrees * M_PI / 180.0;
    options.measure = evolution;
    options.keep_initial_mesh = !html.empty();
    FitResult result = run_fit(points, skeleton, options);
    if (result.report.skeleton_extraction)
      for (const auto& limb : result.report.skeleton_extraction->dropped_limbs)
        warn("the extracted skeleton's limb ending at " + point_text(limb.end) +
             " was left out: its tube overlapped another at " + point_text(limb.overlap) +
             " (the mesh does not reach that part of the scan)");
    write_mesh(output, result.mesh);
    result.report.output_mesh = std::filesystem::absolute(output).string();
    nlohmann::json json = to_json(result.report);
    if (!report.empty()) write_text_atomically(report, json.dump(2) + "\n");
    if (!html.empty()) write_fit_html(result, json);
    print_summary(result.report);
    if (!result.report.verdict) return kExitOk;
    return report_verdict(*result.report.verdict, strict);
  }

  //! The HTML report from what the fit left in memory (the cloud is read again).
  void write_fit_html(const FitResult& result, const nlohmann::json& json) const {
    PointCloud cloud = read_point_cloud(points);
    SkeletonData skeleton_data = result.extracted_skeleton ? *result.extracted_skeleton : read_skeleton(skeleton);
    HtmlReportInput input;
    input.report = &json;
    input.final_mesh = &result.mesh;
    input.initial_mesh = &result.initial_mesh;
    input.cloud = &cloud;
    input.skeleton = &skeleton_data;
    input.title = std::filesystem::path(output).filename().string();
    write_html_report(html, input);
  }

  void print_summary(const FitReport& r) const {
    const MeshStatistics& m = r.metrics ? r.metrics->statistics : r.initial_mesh.statistics;
    std::printf("mesh: %s (%zu vertices, %zu faces, Euler characteristic %ld, %zu irregular vertices)\n",
                output.c_str(), m.vertices, m.faces, m.euler_characteristic, m.irregular_vertices);
    if (r.evolution) {
      const FitReport::Evolution& e = *r.evolution;
      std::printf(
          "backend: %s on %s; error level (mean distance to the cloud's local planes) %.4g -> %.4g after %zu "
          "iterations\n",
          e.backend.c_str(), e.device.c_str(), e.initial_error_level, e.final_error_level(), e.iterations.size());
      if (e.turned_faces && e.turned_faces->faces_before > 0) {
        const TurnedFaceSmoothing& t = *e.turned_faces;
        std::printf(
            "turned faces: %zu facing against the scan's normals (%.2f %% of the area) -> %zu (%.2f %%), %d rounds of "
            "smoothing and %u steps settling\n",
            t.faces_before, 100 * t.area_before, t.faces_after, 100 * t.area_after, t.rounds, t.settle_iterations);
      }
    }
    if (r.evolution && r.metrics) {
      const QualityMetrics& q = *r.metrics;
      std::printf(
          "distances: vertices to their nearest cloud point mean %.4g, 95 %% within %.4g; cloud points to the mesh "
          "mean %.4g, 95 %% within %.4g; %zu pairs of faces cross\n",
          q.mesh_to_cloud.mean, q.mesh_to_cloud.p95, q.cloud_to_mesh.mean, q.cloud_to_mesh.p95,
          q.intersecting_face_pairs);
    }
    if (r.coverage_refinement && r.coverage_refinement->refined) {
      const FitReport::CoverageRefinement& c = *r.coverage_refinement;
      std::string worse;
      for (const auto& name : c.worse) worse += (worse.empty() ? "" : ", ") + name;
      std::printf(
          "refined once for coverage: cloud points to the mesh, 95 %% within %.4g -> %.4g of the median radius "
          "(bound %.4g); %s\n",
          c.uncovered_at_default, c.uncovered_refined, c.bound,
          c.kept ? "the finer fit kept" : ("the default fit kept (finer, worse: " + worse + ")").c_str());
    }
    if (r.surfaces && r.surfaces->cad_file) print_surface_summary(*r.surfaces, true);
    if (!report.empty()) std::printf("report: %s\n", report.c_str());
    if (!html.empty()) std::printf("HTML report: %s\n", html.c_str());
  }
};

int run_generate(const std::string& name, const std::string& directory, const ShapeOptions& options) {
  GeneratedShape shape = generate_shape(name, options);
  write_generated_shape(shape, directory);
  auto [lo, hi] = bounding_box(shape.cloud);
  std::printf("%s: %zu points in [%.3f, %.3f] x [%.3f, %.3f] x [%.3f, %.3f], %zu skeleton nodes\n", name.c_str(),
              shape.cloud.size(), lo.x(), hi.x(), lo.y(), hi.y(), lo.z(), hi.z(), shape.skeleton.nodes.size());
  std::string base = (std::filesystem::path(directory) / name).string();
  std::printf("wrote %s.ply, %s.skeleton.obj, %s.surface.json\n", base.c_str(), base.c_str(), base.c_str());
  return kExitOk;
}

int run_skeleton(const std::string& points_path, const std::string& output, const std::string& json_path,
                 const SkeletonExtractionOptions& options) {
  check_output_path(output, {"obj"});
  if (!json_path.empty()) check_output_path(json_path, {"json"});
  double seconds = 0;
  ExtractedSkeleton extracted = extract_skeleton_from_file(points_path, options, seconds);
  SkeletonReport report = skeleton_report(extracted, points_path, seconds);
  write_skeleton_obj(output, extracted.skeleton);
  if (!json_path.empty()) write_text_atomically(json_path, to_json(report).dump(2) + "\n");
  std::printf(
      "skeleton: %s (%zu nodes, %zu bones: %d junctions, %d ends, %d independent cycles, %d components) in %.3g s\n",
      output.c_str(), extracted.skeleton.nodes.size(), extracted.skeleton.edges.size(), report.junctions, report.ends,
      report.independent_cycles, report.components, seconds);
  if (!json_path.empty()) std::printf("report: %s\n", json_path.c_str());
  return kExitOk;
}

int run_devices() {
#ifdef MCQUAD_WITH_OPENCL
  auto devices = list_devices();
  if (devices.empty()) {
    std::printf("no OpenCL devices found (install an ICD such as pocl-opencl-icd)\n");
    return kExitDevice;
  }
  for (const auto& d : devices)
    std::printf("%d: %s [%s] on %s, %s, %u compute units, %.1f GiB\n", d.index, d.name.c_str(), d.type.c_str(),
                d.platform.c_str(), d.version.c_str(), d.compute_units, d.global_memory / 1073741824.0);
  return kExitOk;
#else
  std::printf("this build of mcquad has no OpenCL backend\n");
  return kExitDevice;
#endif
}

int run_metrics(const std::string& mesh_path, const std::string& points_path, const std::string& skeleton_path,
                const std::string& surface_path, size_t leaf_size, const std::string& json_path, bool strict) {
  QuadMesh mesh = read_mesh(mesh_path);
  PointCloud cloud = read_point_cloud(points_path, true);
  sort_spatially(cloud);  // as fit sorts it: the same figures as its report, and faster (measure.h)
  std::unique_ptr<SkeletonData> skeleton;
  if (!skeleton_path.empty()) skeleton = std::make_unique<SkeletonData>(read_skeleton(skeleton_path));
  MeshMeasurement measured = measure_mesh(mesh, cloud, skeleton.get(), skeleton_path, leaf_size);
  nlohmann::json& metrics = measured.metrics;
  if (!surface_path.empty()) {
    nlohmann::json description;
    try {
      description = nlohmann::json::parse(read_file(surface_path));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(surface_path + ": not valid JSON: " + e.what());
    }
    TubeSurface surface = TubeSurface::from_json(description);
    metrics["true_surface"] = to_json(measure_true_surface_distance(mesh, surface));
    metrics["true_surface"]["cloud_to_mesh_relative_to_local_radius"] =
        to_json(cloud_to_mesh_relative_to_local_radius(mesh, cloud, surface));
  }
  if (!json_path.empty()) write_text_atomically(json_path, metrics.dump(2) + "\n");
  std::printf("%s\n", metrics.dump(2).c_str());
  return report_verdict(measured.verdict, strict);
}

//! Two to four lines on the surfaces: file, seams, distances.
void print_surface_summary(const SurfaceReport& report, bool with_cloud) {
  const SurfaceChecks& checks = report.checks;
  if (report.cad_file) {
    const CadFileReport& file = *report.cad_file;
    std::printf(
        "surfaces: %s (%zu B-spline faces read back, %zu periodic; units: %s; %zu shell(s), %s, %zu free edges)\n",
        file.path.c_str(), file.read_back.faces, checks.periodic_surfaces, file.units.c_str(), file.read_back.shells,
        file.read_back.valid ? "valid" : "NOT VALID", file.read_back.free_edges);
  }
  std::printf(
      "seams: %zu edges, position gap %.3g, tangent-continuous within %.3g deg on %zu, max normal gap %.3g deg "
      "(%.3g deg on smooth parts of the mesh two or more edges from irregular vertices)\n",
      checks.seam_edges, checks.max_position_gap, checks.tangent_tolerance_degrees, checks.seam_edges_within_tolerance,
      checks.max_normal_gap_degrees, checks.max_normal_gap_away_from_irregular_degrees);
  std::printf("distance to the quad mesh: mean %.4g p95 %.4g max %.4g\n", checks.to_mesh.mean, checks.to_mesh.p95,
              checks.to_mesh.max);
  if (with_cloud)
    std::printf("distance to the cloud: mean %.4g p95 %.4g (the quad mesh's own: mean %.4g p95 %.4g)\n",
                checks.to_cloud.mean, checks.to_cloud.p95, checks.mesh_to_cloud.mean, checks.mesh_to_cloud.p95);
}

int run_surfaces(const std::string& mesh_path, const std::string& points_path, const SurfaceOutputs& outputs,
                 const std::string& json_path) {
  check_output_path(outputs.cad_path, cad_extensions());
  if (!outputs.control_nets_path.empty()) check_output_path(outputs.control_nets_path, mesh_extensions());
  if (!json_path.empty()) check_output_path(json_path, {"json"});
  QuadMesh mesh = read_mesh(mesh_path);
  if (mesh.n_faces() == 0) throw InputError(mesh_path + ": the mesh has no faces");
  PointCloud cloud;
  if (!points_path.empty()) cloud = read_point_cloud(points_path);
  VerdictCheck off_cloud;
  SurfaceReport report = export_surfaces(mesh, points_path.empty() ? nullptr : &cloud, outputs, &off_cloud);
  if (!json_path.empty()) write_text_atomically(json_path, to_json(report).dump(2) + "\n");
  print_surface_summary(report, !points_path.empty());
  if (!off_cloud.name.empty()) {
    Verdict verdict;
    add_check(verdict, off_cloud);
    for (const std::string& line : verdict_warnings(verdict)) warn(line);
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mcquad: quad meshes from point clouds and their skeletons by the Monte Carlo method"};
  app.set_version_flag("--version", std::string("mcquad ") + MCQUAD_VERSION);
  app.require_subcommand(1);

  FitCommand fit, init;
  auto* fit_app = app.add_subcommand("fit", "the whole pipeline: initial mesh, Monte Carlo evolution, metrics");
  fit.add_options(fit_app, true);
  auto* init_app = app.add_subcommand("init", "the initial quad mesh only (the paper's Fig. 1)");
  init.add_options(init_app, false);

  std::string shape_name, shape_dir;
  ShapeOptions shape_options;
  std::string shape_help = "synthetic clouds with skeletons and true surfaces:";
  for (const auto& [name, what] : shape_catalogue()) shape_help.append("\n  ").append(name).append(": ").append(what);
  auto* generate_app = app.add_subcommand("generate", shape_help);
  generate_app->add_option("NAME", shape_name, "shape name")->required();
  generate_app->add_option("-o,--output", shape_dir, "output directory")->required();
  generate_app->add_option("--points", shape_options.points, "number of points (0 = the shape's default)")
      ->capture_default_str();
  generate_app->add_option("--noise", shape_options.noise, "noise along the normal, fraction of the tube radius")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  generate_app->add_option("--seed", shape_options.seed, "random seed")->capture_default_str();
  generate_app
      ->add_option("--angle", shape_options.angle_degrees,
                   "y-fork: angle between the branches (0 = 60); fan: between neighbours (0 = 30); "
                   "thin-branch: between the branch and the trunk (0 = 60); degrees")
      ->check(CLI::Range(0.0, 175.0))
      ->capture_default_str();
  generate_app->add_option("--branch-radius", shape_options.branch_radius, "thin-branch: the branch's radius (trunk 1)")
      ->check(CLI::Range(0.05, 0.9))
      ->capture_default_str();
  generate_app->add_option("--arms", shape_options.arms, "star, planar-star: junction valence (3..16)")
      ->check(CLI::Range(3, 16))
      ->capture_default_str();
  generate_app
      ->add_option("--outliers", shape_options.outliers, "fraction of points replaced by outliers off the surface")
      ->check(CLI::Range(0.0, 0.5))
      ->capture_default_str();
  generate_app->add_option("--density-ratio", shape_options.density_ratio, "density falls along x by this factor")
      ->check(CLI::Range(1.0, 1000.0))
      ->capture_default_str();
  generate_app->add_option("--holes", shape_options.holes, "patches of radius r left without points")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  generate_app
      ->add_option("--skeleton-offset", shape_options.skeleton_offset,
                   "move every skeleton node off-centre by this fraction of its radius (the cloud stays)")
      ->check(CLI::Range(0.0, 2.0))
      ->capture_default_str();
  generate_app
      ->add_option("--short-ends", shape_options.short_ends,
                   "pull every skeleton end node back along its chain by this fraction of its radius")
      ->check(CLI::Range(0.0, 5.0))
      ->capture_default_str();

  std::string skeleton_points, skeleton_output, skeleton_json;
  SkeletonExtractionOptions skeleton_options;
  auto* skeleton_app = app.add_subcommand("skeleton", "a curve skeleton of a point cloud, for fit (docs/SKELETON.md)");
  skeleton_app
      ->add_option("POINTS", skeleton_points,
                   "point cloud (.ply, .xyz, .txt, .csv, .obj, .off); normals are not needed")
      ->required();
  skeleton_app->add_option("-o,--output", skeleton_output, "output skeleton (.obj: v and l lines)")->required();
  skeleton_app->add_option("--report", skeleton_json,
                           "write a JSON report here: every node's position, radius and kind");
  skeleton_app
      ->add_option("--voxels", skeleton_options.target_voxels,
                   "voxels the cloud is thinned to (0 = a quarter of the points, at most 40000)")
      ->check(CLI::Range(size_t(0), size_t(2000000)))
      ->capture_default_str();

  app.add_subcommand("devices", "list the OpenCL platforms and devices");

  std::string metrics_mesh, metrics_points, metrics_skeleton, metrics_surface, metrics_json;
  size_t metrics_leaf = FitOptions().leaf_size;
  auto* metrics_app = app.add_subcommand("metrics", "distances both ways, error level, topology and defects of a mesh");
  metrics_app->add_option("MESH", metrics_mesh, "mesh (.obj, .off, .ply, .om)")->required();
  metrics_app->add_option("POINTS", metrics_points, "point cloud")->required();
  metrics_app->add_option("--skeleton", metrics_skeleton,
                          "skeleton: the radius that scales the distance checks, the open ends, and inward faces when "
                          "the cloud has no normals");
  metrics_app
      ->add_option("--leaf-size", metrics_leaf, "maximal points per cell, for the error level (0 = as fit chooses)")
      ->capture_default_str();
  metrics_app->add_option("--surface", metrics_surface,
                          "a generated shape's NAME.surface.json: distances to the true surface");
  metrics_app->add_option("--json", metrics_json, "also write the metrics here");
  bool metrics_strict = false;
  metrics_app->add_flag("--strict", metrics_strict, "exit with code 7 when a check of the verdict fails");

  std::string surfaces_mesh, surfaces_points, surfaces_json;
  SurfaceOutputs surface_outputs;
  auto* surfaces_app =
      app.add_subcommand("surfaces", "B-spline surfaces of a quad mesh, written as STEP or IGES (the paper's Fig. 7d)");
  surfaces_app->add_option("MESH", surfaces_mesh, "quad mesh (.obj, .off, .ply, .om)")->required();
  surfaces_app->add_option("-o,--output", surface_outputs.cad_path, "output (.step, .stp, .iges, .igs)")->required();
  surfaces_app->add_option("--cloud", surfaces_points, "point cloud, to measure the surfaces' distance to it");
  surfaces_app->add_option("--control-nets", surface_outputs.control_nets_path,
                           "also write the control nets (.obj, .off, .ply, .om)");
  surfaces_app
      ->add_option("--tangent-tolerance", surface_outputs.tangent_tolerance_degrees,
                   "normal gap, degrees, under which a seam counts as tangent-continuous")
      ->check(CLI::Range(0.0, 90.0))
      ->capture_default_str();
  surfaces_app->add_option("--json", surfaces_json, "write the surface report here");
  surfaces_app
      ->add_option("--units", surface_outputs.units,
                   "the length unit the CAD file declares; the coordinates are written as they are")
      ->check(CLI::IsMember({"mm", "cm", "m", "um", "in", "ft"}))
      ->capture_default_str();

  std::string report_json, report_mesh, report_html;
  auto* report_app = app.add_subcommand("report", "a fit's JSON report as a self-contained HTML page to look at");
  report_app->add_option("REPORT", report_json, "the JSON report of 'mcquad fit --report'")->required();
  report_app->add_option("-o,--output", report_html, "output (.html)")->required();
  report_app->add_option("--mesh", report_mesh, "the fitted mesh (default: the one the report names in outputs.mesh)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }

  try {
    if (*fit_app) return fit.run(true);
    if (*init_app) return init.run(false);
    if (*generate_app) return run_generate(shape_name, shape_dir, shape_options);
    if (*skeleton_app) return run_skeleton(skeleton_points, skeleton_output, skeleton_json, skeleton_options);
    if (app.got_subcommand("devices")) return run_devices();
    if (*surfaces_app) return run_surfaces(surfaces_mesh, surfaces_points, surface_outputs, surfaces_json);
    if (*report_app) {
      check_output_path(report_html, {"html"});
      write_html_report_from_json(report_json, report_mesh, report_html);
      std::printf("HTML report: %s\n", report_html.c_str());
      return kExitOk;
    }
    if (*metrics_app)
      return run_metrics(metrics_mesh, metrics_points, metrics_skeleton, metrics_surface, metrics_leaf, metrics_json,
                         metrics_strict);
  } catch (const InputError& e) {
    std::fprintf(stderr, "mcquad: error: %s\n", e.what());
    return kExitInput;
  } catch (const UnsupportedError& e) {
    std::fprintf(stderr, "mcquad: unsupported: %s\n", e.what());
    return kExitUnsupported;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "mcquad: device error: %s\n", e.what());
    return kExitDevice;
  } catch (const OutputError& e) {
    std::fprintf(stderr, "mcquad: output error: %s\n", e.what());
    return kExitOutput;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "mcquad: error: out of memory\n");
    return kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mcquad: internal error: %s\n", e.what());
    return kExitInternal;
  }
  return kExitUsage;
}
