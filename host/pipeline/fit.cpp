#include "pipeline/fit.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <future>
#include <optional>

#include "core/errors.h"
#include "cells/cell_facing.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"
#include "mesh/face_intersections.h"
#include "metrics/surface_distance.h"
#include "pipeline/make_backend.h"
#include "pipeline/prepare.h"
#include "skeleton/limb_removal.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {
namespace {

//! Points with normals the verdict judges orientation by: a million pin the
//! inward area down, and 24 bytes each stay small beside any cloud.
constexpr size_t kOrientedSample = 1000000;

//! Writes the mesh after every iteration into `directory` (created).
IterationCallback snapshot_writer(const std::string& directory, const QuadMesh& mesh) {
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw OutputError(directory + ": cannot create directory: " + ec.message());
  return [directory, &mesh](const IterationRecord& record, EvolutionBackend& backend) {
    QuadMesh copy = mesh;
    set_positions(copy, backend.positions());
    char name[32];
    std::snprintf(name, sizeof name, "iteration-%03u.obj", record.iteration);
    write_mesh((std::filesystem::path(directory) / name).string(), copy);
  };
}

//! The OpenCL device set up on another thread (context, queue, program from
//! the cache: 50 ms on PoCL) while this one prepares the mesh and the cells,
//! much of it on one core: on the knot, the median time before the first
//! iteration went 0.489 -> 0.428 s (docs/PERFORMANCE.md). Nothing comes of a
//! failure there: the backend is then made again where it is needed, which
//! reports the failure or warns and falls back as make_backend does, on
//! this thread.
std::future<std::unique_ptr<EvolutionBackend>> start_opencl_backend(const FitOptions& options) {
  if (!options.evolve || options.backend == BackendKind::kSerial) return {};
  return std::async(std::launch::async, [device = options.device]() -> std::unique_ptr<EvolutionBackend> {
    try {
      return make_backend(BackendKind::kOpenCL, device);
    } catch (const std::exception&) {
      return nullptr;
    }
  });
}

//! The stages of one evolution as evolve_mesh times them (after its
//! prefix), named once: a fit refined for coverage renames the first ones.
constexpr const char* kBackendSetupStage = "backend_setup";
constexpr const char* kUploadStage = "upload";
constexpr const char* kEvolutionStage = "evolution";
constexpr const char* kReachStage = "reach_uncovered";
constexpr const char* kTurnedFacesStage = "turned_faces";
constexpr const char* kEvolutionStages[] = {kBackendSetupStage, kUploadStage, kEvolutionStage, kReachStage,
                                            kTurnedFacesStage};

//! Whether `reached` covers `cloud` better than `plain`: its cloud -> mesh
//! 95th percentile (the verdict's coverage, on the reach's sample) lower.
//! Fewer points left uncovered do not make a better fit by themselves; with
//! this test a reach kept makes the verdict's coverage better. It does not
//! catch all: on blob-limbs (OpenCL, seed 2) the kept reach covers the body
//! better and the thin legs worse, 0.294 -> 0.311 of the local radius
//! against the true surface (test Issue14/ReachInTheFit, docs/DESIGN.md).
bool covers_more(const QuadMesh& reached, const QuadMesh& plain, const PointCloud& cloud) {
  const auto p95 = [&](const QuadMesh& mesh) {
    return summarize_distances(cloud_to_mesh_distances(mesh, cloud, kReachSampledPoints)).p95;
  };
  return p95(reached) < p95(plain);
}

//! Runs the evolution on the prepared setup and leaves its positions in
//! `mesh`; its stages are timed as `stage_prefix` + the stage's name. The
//! backend is `early_backend`'s when it holds one (taken), else made here.
//! In robust mode the cloud the evolution left uncovered is then reached
//! for (evolution/uncovered_reach.h) and the faces turned against the scan
//! smoothed (turned_face_smoothing.h); on a scan with normals the fit so
//! reached is kept where, smoothed, the area it turns against them stays
//! within the verdict's bound or no larger than the fit's without the reach,
//! smoothed: on the real armadillo and elephant the reach covered more but
//! turned more; and, with normals or without, where it covers the cloud
//! better (covers_more). `unsmoothed`, if given, gets the kept fit before its
//! smoothing.
FitReport::Evolution evolve_mesh(EvolutionSetup& setup, const FitOptions& options,
                                 const EvolutionParameters& parameters, const ScanOrientation& scan,
                                 const PointCloud& cloud, QuadMesh& mesh, StageTimer& timer,
                                 std::future<std::unique_ptr<EvolutionBackend>>& early_backend,
                                 const std::string& stage_prefix = "", QuadMesh* unsmoothed = nullptr) {
  auto backend = timer.run(stage_prefix + kBackendSetupStage, [&] {
    std::unique_ptr<EvolutionBackend> early = early_backend.valid() ? early_backend.get() : nullptr;
    return early ? std::move(early) : make_backend(options.backend, options.device);
  });
  timer.run(stage_prefix + kUploadStage, [&] {
    backend->load(setup.cells, setup.arrays, setup.regions);
    return 0;
  });
  IterationCallback snapshot;
  if (!options.snapshots_directory.empty() && stage_prefix.empty())
    snapshot = snapshot_writer(options.snapshots_directory, mesh);
  EvolutionResult evolution =
      timer.run(stage_prefix + kEvolutionStage, [&] { return evolve(*backend, setup.arrays, parameters, snapshot); });
  set_positions(mesh, evolution.positions);
  FitReport::Evolution report;
  report.backend = backend->name();
  report.device = backend->device_name();
  report.initial_error_level = evolution.initial_error_level;
  report.iterations = std::move(evolution.iterations);
  report.stop_reason = evolution.stop_reason;
  const bool robust = parameters.mode == EvolutionParameters::Mode::kRobust;
  unsigned next_iteration = unsigned(report.iterations.size());
  std::optional<QuadMesh> reached;
  if (robust && parameters.reach_uncovered && parameters.iterations > 0) {
    reached = mesh;
    report.uncovered_reach = timer.run(stage_prefix + kReachStage, [&] {
      return reach_uncovered_cloud(*backend, setup.arrays, parameters, cloud, *reached, next_iteration);
    });
    if (report.uncovered_reach->rounds == 0) reached.reset();
  }
  const bool smooth = robust && parameters.turned_face_rounds > 0 && !scan.empty();
  if (!smooth) {
    if (reached && covers_more(*reached, mesh, cloud)) {
      mesh = std::move(*reached);
      report.uncovered_reach->kept = true;
    }
    if (unsmoothed) *unsmoothed = mesh;
    return report;
  }
  report.turned_faces = timer.run(stage_prefix + kTurnedFacesStage, [&] {
    if (unsmoothed) *unsmoothed = mesh;
    TurnedFaceSmoothing plain = turn_faces_out(*backend, setup.arrays, parameters, scan, mesh, next_iteration);
    if (!reached) return plain;
    const QuadMesh reached_unsmoothed = *reached;
    TurnedFaceSmoothing smoothed = turn_faces_out(*backend, setup.arrays, parameters, scan, *reached,
                                                  next_iteration + report.uncovered_reach->settle_iterations);
    // The reach may turn more only where the verdict's inward check still
    // passes, and must cover more as the verdict measures it.
    const double allowed = std::max(scan.inward_area_fraction(mesh), VerdictThresholds().inward_area_fraction);
    if (scan.inward_area_fraction(*reached) > allowed || !covers_more(*reached, mesh, cloud)) return plain;
    mesh = std::move(*reached);
    if (unsmoothed) *unsmoothed = reached_unsmoothed;
    report.uncovered_reach->kept = true;
    return smoothed;
  });
  return report;
}

//! Coarse to fine: the evolved mesh refined `levels` more times, the
//! arrays and the skeleton regions made anew for the next evolution.
void refine_evolved_mesh(EvolutionSetup& setup, QuadMesh& mesh, QuadMesh& unsmoothed, FitReport::Evolution& coarse,
                         int levels, StageTimer& timer) {
  timer.run("refine_fitted", [&] {
    refine_fitted_mesh(mesh, levels);
    // Refined, the smoothed coarse fit can cross where the untangling
    // cannot part it (the real armadillo's finer fit: 25 pairs), and the
    // guard keeps what it starts from; the fit before the smoothing is
    // refined too then, and the one with fewer crossing pairs goes on.
    if (coarse.turned_faces && coarse.turned_faces->rounds > 0) {
      size_t crossings = intersecting_face_pairs(mesh).size();
      if (crossings > 0) {
        refine_fitted_mesh(unsmoothed, levels);
        if (intersecting_face_pairs(unsmoothed).size() < crossings) {
          mesh = unsmoothed;
          coarse.turned_faces->undone_for_crossings = true;
        }
      }
    }
    setup.arrays = flatten_mesh(mesh);
    setup.regions = build_skeleton_regions(setup.initial.skeleton, setup.cells, setup.arrays, setup.median_radius);
    return 0;
  });
}

//! How much nearer a smooth surface the chords of a mesh come one
//! Catmull-Clark level finer: their sagitta goes with the edge squared.
constexpr double kChordErrorFallPerLevel = 4.0;

//! `now` is worse than `before` (the same check of another mesh): it fails
//! where that passed, or fails by more.
bool worse(const VerdictCheck& now, const VerdictCheck& before) {
  if (now.passed) return false;
  if (before.passed) return true;
  return now.bound == VerdictCheck::Bound::kAtMost ? now.value > before.value : now.value < before.value;
}

//! Robust mode at the default resolution, once the fit is measured: where
//! its verdict finds the cloud uncovered, by less than one level of
//! refinement can make up, `refine_and_evolve` refines the
//! fitted mesh once, evolves and measures it again (in `report` and
//! `mesh`). The refined fit is kept when it covers the cloud better and no
//! other check is worse: none the default fit passed fails, none it failed
//! has a worse figure. Else the default fit and its report come back: one
//! level finer, the real kitten turned more of its area against the scan's
//! normals (2.55 -> 2.97 %), a fat body's tail loop crossed more (58
//! crossing pairs for 33), both failing the verdict already.
FitReport::CoverageRefinement refine_where_uncovered(FitReport& report, QuadMesh& mesh,
                                                     const std::function<void()>& refine_and_evolve) {
  FitReport::CoverageRefinement coverage;
  const VerdictCheck* found = report.verdict->find("uncovered_cloud");
  if (!found) return coverage;
  const VerdictCheck uncovered = *found;  // the verdict is measured anew below
  coverage.bound = uncovered.threshold;
  coverage.uncovered_at_default = uncovered.value;
  // One level halves the edges and quarters the chords' distance from a
  // smooth surface: a fit uncovered by more is missing what the mesh does
  // not reach at all (an ear with no bone, a palm's outline), which a finer
  // mesh does not reach either (on the hand, 0.23 -> 0.10 of the median
  // radius, and 2.6 times the time).
  if (uncovered.passed || uncovered.value > kChordErrorFallPerLevel * uncovered.threshold) return coverage;
  // What the default fit's report says of it, for when it is kept after all.
  FitReport::Evolution default_evolution = *report.evolution;
  QualityMetrics default_metrics = *report.metrics;
  Verdict default_verdict = *report.verdict;
  QuadMesh default_mesh = mesh;
  refine_and_evolve();
  coverage.refined = true;
  coverage.uncovered_refined = report.verdict->find(uncovered.name)->value;
  for (const VerdictCheck& check : default_verdict.checks) {
    const VerdictCheck* now = report.verdict->find(check.name);
    if (now && check.name != uncovered.name && worse(*now, check)) coverage.worse.push_back(check.name);
  }
  coverage.kept = coverage.uncovered_refined < coverage.uncovered_at_default && coverage.worse.empty();
  if (coverage.kept) {
    report.initial_mesh.levels_after_coarse_evolution = 1;
  } else {
    report.evolution = std::move(default_evolution);
    report.coarse_evolution.reset();
    report.metrics = std::move(default_metrics);
    report.verdict = std::move(default_verdict);
    mesh = default_mesh;
  }
  return coverage;
}

//! The most limbs a fit leaves out of the skeleton it extracted.
constexpr size_t kMaxDroppedLimbs = 4;

//! `prepare()` on the skeleton the fit extracted; where its initial mesh
//! overlaps itself (two tubes too close: two of the real armadillo's
//! limbs), again without the limb nearest the overlap (skeleton and graph
//! updated, the limb noted in `dropped`), at most kMaxDroppedLimbs times. A
//! mesh of the rest, which the verdict judges, rather than none; a skeleton
//! the user gave is never changed.
EvolutionSetup prepare_without_overlapping_limbs(const std::function<EvolutionSetup()>& prepare, SkeletonData& skeleton,
                                                 SkeletonGraph& graph, const std::string& source,
                                                 std::vector<SkeletonReport::DroppedLimb>& dropped) {
  while (true) {
    try {
      return prepare();
    } catch (const OverlapError& overlap) {
      const Eigen::Vector3d site(overlap.site[0], overlap.site[1], overlap.site[2]);
      std::optional<Eigen::Vector3d> end;
      if (dropped.size() < kMaxDroppedLimbs) end = remove_limb_nearest(skeleton, site);
      if (!end) throw;
      dropped.push_back({*end, site});
      graph = build_skeleton_graph(skeleton, source);
    }
  }
}

//! The stages from the graph on, with the reading already timed.
FitResult fit_loaded(FitInput input, const FitOptions& options, StageTimer& timer) {
  PointCloud& cloud = input.cloud;
  const std::string& points_path = input.points_name;
  FitResult result;
  FitReport& report = result.report;
  if (input.skeleton.nodes.empty() && input.skeleton_name.empty()) {
    // Before the points are sorted: the same cloud order, hence the same
    // skeleton, as `mcquad skeleton` reading the same file.
    ExtractedSkeleton skeleton = timer.run("extract_skeleton", [&] { return extract_skeleton(cloud, points_path); });
    report.skeleton_extraction = skeleton_report(skeleton, points_path, timer.seconds("extract_skeleton"));
    input.skeleton = skeleton.skeleton;
    result.extracted_skeleton = std::move(skeleton.skeleton);
    input.skeleton_name = "the skeleton extracted from " + points_path;
  }
  const std::string& skeleton_path = input.skeleton_name;
  std::future<std::unique_ptr<EvolutionBackend>> early_backend = start_opencl_backend(options);
  // The scan's normals judge the mesh's orientation at the end; a sample of
  // them is enough, and the rest need not be sorted and carried along.
  OrientedSample oriented =
      cloud.oriented.empty() ? oriented_sample(cloud, kOrientedSample) : std::move(cloud.oriented);
  cloud.oriented = OrientedSample();
  std::vector<Eigen::Vector3f>().swap(cloud.normals);
  sort_spatially(oriented);  // now, while memory is low: its index builds 3x faster in spatial order
  timer.run("sort_points", [&] {
    sort_spatially(cloud);
    return 0;
  });
  SkeletonGraph graph = build_skeleton_graph(input.skeleton, skeleton_path);

  // The initial mesh alone (mcquad init) needs no cells.
  SetupScope scope = options.evolve    ? SetupScope::kEvolution
                     : options.measure ? SetupScope::kCells
                                       : SetupScope::kInitialMesh;
  // Coarse to fine in robust mode: finer meshes start from the default
  // resolution's fit, refined, instead of from the rough mesh 0.3 r inside
  // the cloud, which their steps reach slowly (docs/DESIGN.md).
  const InitialMeshOptions initial_options = effective_initial_options(options);
  // The cells face the scan's normals only where the step will look (robust mode, facing cells on).
  const bool robust = options.evolution.mode == EvolutionParameters::Mode::kRobust;
  const bool facing = robust && options.evolution.facing_cells;
  const OrientedSample no_normals;
  // One index over the scan's normals, for the smoothing of turned faces
  // and the verdict alike (about 20 ms on the knot's 413,696 points); none for
  // the initial mesh alone.
  const bool orient = options.measure || (options.evolve && robust && options.evolution.turned_face_rounds > 0);
  std::optional<ScanOrientation> scan;
  timer.run("orientation_index", [&] {
    scan.emplace(orient ? oriented : no_normals);
    return 0;
  });
  auto prepare = [&] {
    return prepare_evolution(graph, cloud, initial_options, options.leaf_size, skeleton_path, scope, &timer,
                             facing ? &oriented : &no_normals);
  };
  EvolutionSetup setup = result.extracted_skeleton
                             ? prepare_without_overlapping_limbs(prepare, input.skeleton, graph, skeleton_path,
                                                                 report.skeleton_extraction->dropped_limbs)
                             : prepare();
  if (result.extracted_skeleton) result.extracted_skeleton = input.skeleton;
  if (!options.construction_skeleton.empty())
    write_skeleton_obj(options.construction_skeleton,
                       SkeletonData{setup.initial.skeleton.graph.positions, setup.initial.skeleton.graph.edges});
  // OpenMesh meshes have no move operations, so this is a copy; the
  // original goes at once (228 MiB for a mesh of 2.26 million vertices).
  result.mesh = setup.initial.mesh;
  if (options.keep_initial_mesh) result.initial_mesh = setup.initial.mesh;
  setup.initial.mesh.clear();

  EvolutionParameters parameters = options.evolution;
  if (parameters.epsilon <= 0) parameters.epsilon = automatic_epsilon(setup.median_radius);
  report.inputs = {points_path,        skeleton_path,      cloud.size(),
                   graph.node_count(), graph.edges.size(), graph.component_count};
  report.parameters = {options, parameters.epsilon, setup.median_radius,
                       cell_leaf_size(options.leaf_size, cloud.size())};
  report.initial_mesh = {setup.initial.open_ends, setup.initial.refinement_levels, mesh_statistics(result.mesh),
                         setup.initial.finer_levels, setup.initial.inset_ports};
  if (setup.cells.cell_count() > 0)
    report.cells = FitReport::Cells{setup.cells.cell_count(), setup.cells.node_count(), setup.cells.depth,
                                    double(setup.cells.byte_size()) / 1e6, facing_fraction(setup.cells)};
  QuadMesh unsmoothed;
  if (options.evolve && setup.initial.finer_levels > 0) {
    report.coarse_evolution = evolve_mesh(setup, options, parameters, *scan, cloud, result.mesh, timer, early_backend,
                                          "coarse_", &unsmoothed);
    refine_evolved_mesh(setup, result.mesh, unsmoothed, *report.coarse_evolution, setup.initial.finer_levels, timer);
  }
  // At the default resolution, a mesh that leaves the cloud uncovered by
  // the verdict's bound (a flat end's rim, a flat cross-section's narrow
  // sides: sharper than 16 vertices round the median tube follow) is
  // refined once and evolved again, as a finer fit would be, and kept when
  // it is the better mesh (docs/DESIGN.md).
  const bool default_resolution = options.initial.resolution <= 0 && options.initial.target_vertices == 0;
  const bool may_refine = options.evolve && options.measure && robust && parameters.refine_uncovered &&
                          default_resolution && setup.initial.finer_levels == 0;
  EvolutionParameters refined_parameters = parameters;
  refined_parameters.curvature_at_start = true;
  if (options.evolve)
    report.evolution = evolve_mesh(setup, options, report.coarse_evolution ? refined_parameters : parameters, *scan,
                                   cloud, result.mesh, timer, early_backend, "", may_refine ? &unsmoothed : nullptr);
  auto measure = [&](const std::string& stage) {
    report.metrics = timer.run(stage, [&] { return measure_quality(result.mesh, cloud, setup.cells, &graph, &*scan); });
    report.verdict = judge_mesh(*report.metrics, setup.median_radius, setup.initial.open_ends);
  };
  if (options.measure) measure("metrics");
  if (may_refine) {
    report.coverage_refinement = refine_where_uncovered(report, result.mesh, [&] {
      for (const char* stage : kEvolutionStages) timer.rename(stage, std::string("coarse_") + stage);
      timer.rename("metrics", "coarse_metrics");
      report.coarse_evolution = std::move(report.evolution);
      refine_evolved_mesh(setup, result.mesh, unsmoothed, *report.coarse_evolution, 1, timer);
      report.evolution =
          evolve_mesh(setup, options, refined_parameters, *scan, cloud, result.mesh, timer, early_backend);
      measure("metrics");
    });
  }
  if (!options.surfaces.cad_path.empty() || !options.surfaces.control_nets_path.empty()) {
    VerdictCheck off_cloud;
    report.surfaces = timer.run("surfaces", [&] {
      return export_surfaces(result.mesh, &cloud, options.surfaces, report.verdict ? &off_cloud : nullptr);
    });
    if (report.verdict && !off_cloud.name.empty()) add_check(*report.verdict, std::move(off_cloud));
  }
  report.stages = timer.records();
  report.peak_resident_megabytes = peak_resident_megabytes();
  return result;
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

}  // namespace mcquad
