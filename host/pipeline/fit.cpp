#include "pipeline/fit.h"

#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <filesystem>

#include "cells/cell_tree.h"
#include "core/errors.h"
#include "core/progress.h"
#include "evolution/evolve.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"
#include "mesh/mesh_arrays.h"
#include "pipeline/make_backend.h"
#include "pipeline/prepare.h"
#include "pipeline/skeleton_extraction.h"
#include "pipeline/surfaces.h"
#include "surfaces/cad_model.h"
#include "metrics/mesh_metrics.h"
#include "metrics/verdict.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {
namespace {

double peak_resident_megabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

//! Resident memory now, from /proc/self/statm (0 where there is none).
double current_resident_megabytes() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

//! Times named stages into the report.
class StageTimer {
 public:
  template <typename F>
  auto run(const std::string& stage, F&& work) {
    auto start = std::chrono::steady_clock::now();
    struct Record {
      StageTimer* timer;
      std::string stage;
      std::chrono::steady_clock::time_point start;
      ~Record() {
        timer->seconds[stage] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        timer->peak_megabytes[stage] = peak_resident_megabytes();
        timer->resident_megabytes[stage] = current_resident_megabytes();
      }
    } record{this, stage, start};
    report_stage(stage, false);
    auto result = work();
    report_stage(stage, true, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return result;
  }
  nlohmann::json seconds = nlohmann::json::object();
  //! Peak resident memory of the process when each stage ended: the first
  //! stage at the final peak is the one that set it.
  nlohmann::json peak_megabytes = nlohmann::json::object();
  nlohmann::json resident_megabytes = nlohmann::json::object();
};

nlohmann::json parameters_json(const FitOptions& o, double epsilon, double median_radius, size_t leaf_size) {
  const auto& e = o.evolution;
  const bool robust = e.mode == EvolutionParameters::Mode::kRobust;
  return {{"mode", robust ? "robust" : "paper"},
          {"relaxation", e.relaxation},
          {"projection", robust && e.mean_projection ? "mean" : "min"},
          {"fill_holes", robust && e.fill_holes},
          {"crossing_guard", robust && e.crossing_guard},
          {"held_back_relaxation", robust && e.crossing_guard ? e.held_back_relaxation : 0.0},
          {"own_cells", robust && e.own_cells},
          {"local_epsilon", robust && e.local_epsilon},
          {"hit_band", robust ? e.hit_band : 0.0},
          {"cones", e.cones},
          {"generators", e.generators},
          {"alpha_max", e.alpha_max},
          {"samples", e.samples},
          {"epsilon", epsilon},
          {"epsilon_automatic", e.epsilon <= 0},
          {"iterations", e.iterations},
          {"tolerance", e.tolerance},
          {"seed", e.seed},
          {"leaf_size", leaf_size},
          {"leaf_size_automatic", o.leaf_size == 0},
          {"start_fraction", o.initial.start_fraction},
          {"resolution", o.initial.resolution},
          {"target_vertices", o.initial.target_vertices},
          {"ends", o.initial.ends == EndMode::kAuto ? "auto" : o.initial.ends == EndMode::kOpen ? "open" : "capped"},
          {"min_junction_angle_degrees", o.initial.min_junction_angle * 180.0 / M_PI},
          {"median_radius", median_radius}};
}

constexpr double kDegrees = 180.0 / M_PI;

//! Points with normals the verdict judges orientation by: a million pin the
//! inward area down, and 24 bytes each stay small beside any cloud.
constexpr size_t kOrientedSample = 1000000;

//! Every ranged option of fit, in user units.
constexpr OptionRange kOptionRanges[] = {
    {"start_fraction", 0.05, 0.95}, {"resolution", 0, HUGE_VAL},   {"min_junction_angle", 0, 120},
    {"relaxation", 0, 1},           {"held_back_relaxation", 0, 1}, {"hit_band", 0, 1},
    {"tolerance", 0, HUGE_VAL},     {"cones", 1, 64},               {"generators", 1, 64},
    {"alpha_max", 0, 89},           {"samples", 1, 1024},           {"epsilon", 0, HUGE_VAL},
    {"leaf_size", 0, double(size_t(1) << 20)},
};

void check_range(const char* option, double value) {
  const OptionRange& range = fit_option_range(option);
  // Angles come back from radians with a rounding error; an ulp over the bound is the bound.
  double slack = 1e-9 * std::max(1.0, std::abs(range.high));
  if (!(value >= range.low - slack && value <= range.high + slack))
    throw InputError(std::string(option) + ": " + std::to_string(value) + " is outside [" + std::to_string(range.low) +
                     ", " + std::to_string(range.high) + "]");
}

//! Options out of range or contradicting each other, refused before any
//! work. The CLI checks the same ranges while parsing; this holds them for
//! every other caller (the Python package).
void check_fit_options(const FitOptions& options) {
  const auto& e = options.evolution;
  const auto& i = options.initial;
  check_range("start_fraction", i.start_fraction);
  check_range("resolution", i.resolution);
  check_range("min_junction_angle", i.min_junction_angle * kDegrees);
  check_range("relaxation", e.relaxation);
  check_range("held_back_relaxation", e.held_back_relaxation);
  check_range("hit_band", e.hit_band);
  check_range("tolerance", e.tolerance);
  check_range("cones", e.cones);
  check_range("generators", e.generators);
  check_range("alpha_max", e.alpha_max * kDegrees);
  check_range("samples", e.samples);
  check_range("epsilon", e.epsilon);
  check_range("leaf_size", double(options.leaf_size));
  if (options.evolve && i.stage != "refined") throw InputError("--stage applies to 'mcquad init' only");
  check_cad_unit(options.surfaces.units);
}

//! The stages from the graph on, with the reading already timed.
FitResult fit_loaded(FitInput input, const FitOptions& options, StageTimer& timer) {
  PointCloud& cloud = input.cloud;
  const std::string& points_path = input.points_name;
  std::optional<nlohmann::json> extraction_report;
  std::optional<SkeletonData> extracted;
  if (input.skeleton.nodes.empty() && input.skeleton_name.empty()) {
    // Before the points are sorted: the same cloud order, hence the same
    // skeleton, as `mcquad skeleton` reading the same file.
    ExtractedSkeleton skeleton = timer.run("extract_skeleton", [&] { return extract_skeleton(cloud, points_path); });
    extraction_report = skeleton_report(skeleton, points_path, timer.seconds["extract_skeleton"].get<double>());
    input.skeleton = skeleton.skeleton;
    extracted = std::move(skeleton.skeleton);
    input.skeleton_name = "the skeleton extracted from " + points_path;
  }
  const std::string& skeleton_path = input.skeleton_name;
  // The scan's normals judge the mesh's orientation at the end; a sample of
  // them is enough, and the rest need not be sorted and carried along.
  OrientedSample oriented = cloud.oriented.empty() ? oriented_sample(cloud, kOrientedSample) : std::move(cloud.oriented);
  cloud.oriented = OrientedSample();
  std::vector<Eigen::Vector3f>().swap(cloud.normals);
  timer.run("sort_points", [&] { sort_spatially(cloud); return 0; });
  SkeletonGraph graph = build_skeleton_graph(input.skeleton, skeleton_path);
  // The index serves the radii and the initial mesh, then goes before the cells are built.
  auto cloud_index = timer.run("point_index", [&] { return std::make_unique<PointIndex<float>>(cloud.points); });
  BoneAssignment bones = timer.run("radius", [&] { return assign_points_to_bones(graph, cloud, skeleton_path, cloud_index.get()); });
  double median_radius = median_bone_radius(bones);
  bones.release_per_point();  // only the radii are needed from here on

  InitialMesh initial = timer.run("initial_mesh", [&] { return build_initial_mesh(graph, bones, cloud, options.initial, skeleton_path, cloud_index.get()); });
  cloud_index.reset();
  if (!options.construction_skeleton.empty()) {
    SkeletonData built{initial.skeleton.graph.positions, initial.skeleton.graph.edges};
    write_skeleton_obj(options.construction_skeleton, built);
  }
  FitResult result;
  result.extracted_skeleton = std::move(extracted);
  // OpenMesh meshes have no move operations, so this is a copy; the original
  // goes at once (228 MiB for a mesh of 2.26 million vertices).
  result.mesh = initial.mesh;
  if (options.keep_initial_mesh) result.initial_mesh = initial.mesh;
  initial.mesh.clear();
  // The initial mesh alone (mcquad init) needs no cells.
  CellTree cells;
  const size_t leaf_size = cell_leaf_size(options.leaf_size, cloud.size());
  if (options.evolve || options.measure) {
    cells = timer.run("cells", [&] { return build_cell_tree(cloud, leaf_size); });
    // nanoflann allocates its tree nodes in small pooled blocks that glibc
    // keeps after they are freed (about 70 MiB at 10^7 points); give them
    // back before the device and the metrics add their own.
    malloc_trim(0);
  }

  EvolutionParameters parameters = options.evolution;
  if (parameters.epsilon <= 0) parameters.epsilon = automatic_epsilon(median_radius);
  nlohmann::json report;
  report["inputs"] = {{"points", points_path}, {"skeleton", skeleton_path}, {"point_count", cloud.size()},
                      {"skeleton_nodes", graph.node_count()}, {"skeleton_bones", graph.edges.size()},
                      {"skeleton_components", graph.component_count}};
  report["parameters"] = parameters_json(options, parameters.epsilon, median_radius, leaf_size);
  if (extraction_report) report["skeleton_extraction"] = std::move(*extraction_report);
  report["initial_mesh"] = {{"open_ends", initial.open_ends}, {"refinement_levels", initial.refinement_levels},
                            {"statistics", to_json(mesh_statistics(result.mesh))}};
  if (cells.cell_count() > 0)
    report["cells"] = {{"cells", cells.cell_count()}, {"tree_nodes", cells.node_count()}, {"depth", cells.depth},
                       {"megabytes", double(cells.byte_size()) / 1e6}};

  if (options.evolve) {
    MeshArrays arrays = flatten_mesh(result.mesh);
    auto backend = timer.run("backend_setup", [&] { return make_backend(options.backend, options.device); });
    SkeletonRegions regions = timer.run("regions", [&] {
      return build_skeleton_regions(initial.skeleton, cells, arrays, median_radius);
    });
    timer.run("upload", [&] { backend->load(cells, arrays, regions); return 0; });
    IterationCallback snapshot;
    if (!options.snapshots_directory.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(options.snapshots_directory, ec);
      if (ec) throw OutputError(options.snapshots_directory + ": cannot create directory: " + ec.message());
      snapshot = [&](const IterationRecord& record, EvolutionBackend& b) {
        QuadMesh copy = result.mesh;
        set_positions(copy, b.positions());
        char name[32];
        std::snprintf(name, sizeof name, "iteration-%03u.obj", record.iteration);
        write_mesh((std::filesystem::path(options.snapshots_directory) / name).string(), copy);
      };
    }
    EvolutionResult evolution = timer.run("evolution", [&] { return evolve(*backend, arrays, parameters, snapshot); });
    set_positions(result.mesh, evolution.positions);
    nlohmann::json iterations = nlohmann::json::array();
    for (const auto& r : evolution.iterations)
      iterations.push_back({{"iteration", r.iteration}, {"error_level", r.error_level}, {"seconds", r.seconds},
                            {"step_seconds", r.step_seconds}, {"error_seconds", r.error_seconds},
                            {"guard_seconds", r.guard_seconds}, {"held_back_vertices", r.held_back_vertices}});
    report["backend"] = {{"name", backend->name()}, {"device", backend->device_name()}};
    report["evolution"] = {{"initial_error_level", evolution.initial_error_level},
                           {"iterations", iterations},
                           {"stop_reason", evolution.stop_reason},
                           {"final_error_level", evolution.iterations.empty() ? evolution.initial_error_level
                                                                             : evolution.iterations.back().error_level}};
  }
  if (options.measure) {
    QualityMetrics quality = timer.run("metrics", [&] { return measure_quality(result.mesh, cloud, cells, &graph, &oriented); });
    report["metrics"] = to_json(quality);
    result.verdict = judge_mesh(quality, median_radius, initial.open_ends);
    report["verdict"] = to_json(*result.verdict);
  }
  if (!options.surfaces.cad_path.empty() || !options.surfaces.control_nets_path.empty()) {
    VerdictCheck off_cloud;
    report["surfaces"] = timer.run("surfaces", [&] {
      return export_surfaces(result.mesh, &cloud, options.surfaces, result.verdict ? &off_cloud : nullptr);
    });
    if (result.verdict && !off_cloud.name.empty()) {
      add_check(*result.verdict, std::move(off_cloud));
      report["verdict"] = to_json(*result.verdict);
    }
  }
  report["timings_seconds"] = timer.seconds;
  report["peak_resident_megabytes_after_stage"] = timer.peak_megabytes;
  report["resident_megabytes_after_stage"] = timer.resident_megabytes;
  report["peak_resident_megabytes"] = peak_resident_megabytes();
  report["version"] = MCQUAD_VERSION;
  result.report = std::move(report);
  return result;
}

template <typename Enum>
Enum from_name(const std::string& name, const std::string& option,
               std::initializer_list<std::pair<const char*, Enum>> words) {
  std::string accepted;
  for (const auto& [word, value] : words) {
    if (name == word) return value;
    accepted += std::string(accepted.empty() ? "" : ", ") + word;
  }
  throw InputError(option + ": '" + name + "' is not one of " + accepted);
}

}  // namespace

FitResult run_fit(const std::string& points_path, const std::string& skeleton_path, const FitOptions& options) {
  check_fit_options(options);
  StageTimer timer;
  FitInput input;
  input.points_name = points_path;
  input.skeleton_name = skeleton_path;
  input.cloud = timer.run("read_points", [&] { return read_point_cloud(points_path, false, kOrientedSample); });
  if (!skeleton_path.empty()) input.skeleton = timer.run("read_skeleton", [&] { return read_skeleton(skeleton_path); });
  return fit_loaded(std::move(input), options, timer);
}

FitResult run_fit(FitInput input, const FitOptions& options) {
  check_fit_options(options);
  check_point_cloud(input.cloud, input.points_name);
  StageTimer timer;
  return fit_loaded(std::move(input), options, timer);
}

const OptionRange& fit_option_range(const std::string& name) {
  for (const OptionRange& range : kOptionRanges)
    if (name == range.name) return range;
  throw InputError("no range is defined for the option '" + name + "'");
}

EndMode end_mode_from_name(const std::string& name, const std::string& option) {
  return from_name<EndMode>(name, option, {{"auto", EndMode::kAuto}, {"open", EndMode::kOpen}, {"capped", EndMode::kCapped}});
}

BackendKind backend_from_name(const std::string& name, const std::string& option) {
  return from_name<BackendKind>(name, option,
                                {{"auto", BackendKind::kAuto}, {"serial", BackendKind::kSerial}, {"opencl", BackendKind::kOpenCL}});
}

EvolutionParameters::Mode evolution_mode_from_name(const std::string& name, const std::string& option) {
  using Mode = EvolutionParameters::Mode;
  return from_name<Mode>(name, option, {{"robust", Mode::kRobust}, {"paper", Mode::kPaper}});
}

}  // namespace mcquad
