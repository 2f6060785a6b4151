#include "pipeline/fit.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "cells/cell_tree.h"
#include "core/errors.h"
#include "evolution/evolve.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "pipeline/surfaces.h"
#include "io/skeleton_io.h"
#include "mesh/mesh_arrays.h"
#include "pipeline/prepare.h"
#include "metrics/mesh_metrics.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {
namespace {

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
      ~Record() { timer->seconds[stage] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); }
    } record{this, stage, start};
    return work();
  }
  nlohmann::json seconds = nlohmann::json::object();
};

nlohmann::json parameters_json(const FitOptions& o, double epsilon, double median_radius) {
  const auto& e = o.evolution;
  return {{"mode", e.mode == EvolutionParameters::Mode::kPaper ? "paper" : "robust"},
          {"relaxation", e.relaxation},
          {"cones", e.cones},
          {"generators", e.generators},
          {"alpha_max", e.alpha_max},
          {"samples", e.samples},
          {"epsilon", epsilon},
          {"epsilon_automatic", e.epsilon <= 0},
          {"iterations", e.iterations},
          {"tolerance", e.tolerance},
          {"seed", e.seed},
          {"leaf_size", o.leaf_size},
          {"start_fraction", o.initial.start_fraction},
          {"resolution", o.initial.resolution},
          {"target_vertices", o.initial.target_vertices},
          {"ends", o.initial.ends == EndMode::kAuto ? "auto" : o.initial.ends == EndMode::kOpen ? "open" : "capped"},
          {"median_radius", median_radius}};
}

}  // namespace

FitResult run_fit(const std::string& points_path, const std::string& skeleton_path, const FitOptions& options) {
  if (options.evolve && options.initial.stage != "refined") throw InputError("--stage applies to 'mcquad init' only");
  StageTimer timer;
  PointCloud cloud = timer.run("read_points", [&] { return read_point_cloud(points_path); });
  timer.run("sort_points", [&] { sort_spatially(cloud); return 0; });
  SkeletonData skeleton_data = timer.run("read_skeleton", [&] { return read_skeleton(skeleton_path); });
  SkeletonGraph graph = build_skeleton_graph(skeleton_data, skeleton_path);
  PointIndex<float> cloud_index = timer.run("point_index", [&] { return PointIndex<float>(cloud.points); });
  BoneAssignment bones = timer.run("radius", [&] { return assign_points_to_bones(graph, cloud, skeleton_path, &cloud_index); });
  double median_radius = median_bone_radius(bones);
  bones.release_per_point();  // only the radii are needed from here on

  InitialMesh initial = timer.run("initial_mesh", [&] { return build_initial_mesh(graph, bones, cloud, options.initial, skeleton_path, &cloud_index); });
  if (!options.construction_skeleton.empty()) {
    SkeletonData built{initial.skeleton.graph.positions, initial.skeleton.graph.edges};
    write_skeleton_obj(options.construction_skeleton, built);
  }
  FitResult result;
  result.mesh = std::move(initial.mesh);
  // The initial mesh alone (mcquad init) needs no cells.
  CellTree cells;
  if (options.evolve || options.measure) cells = timer.run("cells", [&] { return build_cell_tree(cloud, options.leaf_size); });

  EvolutionParameters parameters = options.evolution;
  if (parameters.epsilon <= 0) parameters.epsilon = automatic_epsilon(median_radius);
  nlohmann::json report;
  report["inputs"] = {{"points", points_path}, {"skeleton", skeleton_path}, {"point_count", cloud.size()},
                      {"skeleton_nodes", graph.node_count()}, {"skeleton_bones", graph.edges.size()},
                      {"skeleton_components", graph.component_count}};
  report["parameters"] = parameters_json(options, parameters.epsilon, median_radius);
  report["initial_mesh"] = {{"open_ends", initial.open_ends}, {"refinement_levels", initial.refinement_levels},
                            {"statistics", to_json(mesh_statistics(result.mesh))}};
  if (cells.cell_count() > 0)
    report["cells"] = {{"cells", cells.cell_count()}, {"tree_nodes", cells.node_count()}, {"depth", cells.depth},
                       {"megabytes", double(cells.byte_size()) / 1e6}};

  if (options.evolve) {
    MeshArrays arrays = flatten_mesh(result.mesh);
    auto backend = timer.run("backend_setup", [&] { return make_backend(options.backend, options.device); });
    timer.run("upload", [&] { backend->load(cells, arrays); return 0; });
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
    EvolutionResult evolution = timer.run("evolution", [&] { return evolve(*backend, parameters, snapshot); });
    set_positions(result.mesh, evolution.positions);
    nlohmann::json iterations = nlohmann::json::array();
    for (const auto& r : evolution.iterations)
      iterations.push_back({{"iteration", r.iteration}, {"error_level", r.error_level}, {"seconds", r.seconds},
                            {"step_seconds", r.step_seconds}, {"error_seconds", r.error_seconds}});
    report["backend"] = {{"name", backend->name()}, {"device", backend->device_name()}};
    report["evolution"] = {{"initial_error_level", evolution.initial_error_level},
                           {"iterations", iterations},
                           {"stop_reason", evolution.stop_reason},
                           {"final_error_level", evolution.iterations.empty() ? evolution.initial_error_level
                                                                             : evolution.iterations.back().error_level}};
  }
  if (options.measure) {
    report["metrics"] = timer.run("metrics", [&] { return to_json(measure_quality(result.mesh, cloud, cells, &graph)); });
  }
  if (!options.surfaces.cad_path.empty() || !options.surfaces.control_nets_path.empty())
    report["surfaces"] = timer.run("surfaces", [&] { return export_surfaces(result.mesh, &cloud, options.surfaces); });
  report["timings_seconds"] = timer.seconds;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  report["peak_resident_megabytes"] = double(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
  report["version"] = MCQUAD_VERSION;
  result.report = std::move(report);
  return result;
}

}  // namespace mcquad
