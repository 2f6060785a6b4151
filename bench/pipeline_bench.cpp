// Stage-by-stage benchmarks on the paper's Fig. 7 stand-in (torus-knot tube,
// 413,696 points) and on scaled clouds and meshes. Inputs are generated once
// into $MCQUAD_BENCH_DIR (default /tmp/mcquad-bench) and reused.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <memory>

#include "cells/cell_tree.h"
#include "mesh/crossing_guard.h"
#include "evolution/evolve.h"
#include "evolution/serial_backend.h"
#include "generate/shapes.h"
#include "io/mesh_io.h"
#include "io/point_cloud_io.h"
#include "io/skeleton_io.h"
#include "mesh/initial_mesh.h"
#include "mesh/mesh_arrays.h"
#include "mesh/refinement.h"
#include "metrics/mesh_metrics.h"
#include "pipeline/fit.h"
#include "pipeline/prepare.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/cloud_skeleton.h"
#ifdef MCQUAD_WITH_OPENCL
#include "opencl/opencl_backend.h"
#endif

namespace {

using namespace mcquad;

std::string bench_dir() {
  const char* dir = std::getenv("MCQUAD_BENCH_DIR");
  std::string path = dir ? dir : "/tmp/mcquad-bench";
  std::filesystem::create_directories(path);
  return path;
}

//! The torus knot with `points` points, generated once and cached on disk.
std::string knot_cloud(size_t points) {
  std::string dir = bench_dir() + "/knot-" + std::to_string(points);
  if (!std::filesystem::exists(dir + "/torus-knot.ply")) {
    ShapeOptions options;
    options.points = points;
    write_generated_shape(generate_shape("torus-knot", options), dir);
  }
  return dir;
}

//! Everything up to the evolution, built once per (points, vertices).
struct Prepared {
  PointCloud cloud;
  SkeletonGraph graph;
  EvolutionSetup setup;
  EvolutionParameters parameters;
};

Prepared& prepared(size_t points, size_t vertices) {
  static std::map<std::pair<size_t, size_t>, std::unique_ptr<Prepared>> cache;
  auto& slot = cache[{points, vertices}];
  if (slot) return *slot;
  std::string dir = knot_cloud(points);
  auto p = std::make_unique<Prepared>();
  p->cloud = read_point_cloud(dir + "/torus-knot.ply");
  sort_spatially(p->cloud);  // as the pipeline does
  p->graph = build_skeleton_graph(read_skeleton(dir + "/torus-knot.skeleton.obj"), "knot");
  InitialMeshOptions options;
  options.target_vertices = vertices;
  p->setup = prepare_evolution(p->graph, p->cloud, options, FitOptions().leaf_size, "knot");
  p->parameters.epsilon = 0.8;  // the paper's Fig. 7 value
  slot = std::move(p);
  return *slot;
}

constexpr size_t kPaperPoints = 413696;

void BM_SortSpatially(benchmark::State& state) {
  PointCloud cloud = read_point_cloud(knot_cloud(size_t(state.range(0))) + "/torus-knot.ply");
  for (auto _ : state) {
    state.PauseTiming();
    PointCloud copy = cloud;
    state.ResumeTiming();
    sort_spatially(copy);
  }
}

void BM_ReadPly(benchmark::State& state) {
  std::string path = knot_cloud(size_t(state.range(0))) + "/torus-knot.ply";
  for (auto _ : state) benchmark::DoNotOptimize(read_point_cloud(path));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
}

void BM_CellTree(benchmark::State& state) {
  const PointCloud& cloud = prepared(size_t(state.range(0)), 0).cloud;
  for (auto _ : state) benchmark::DoNotOptimize(build_cell_tree(cloud, cell_leaf_size(0, cloud.size())));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(cloud.size()));
}

// nanoflann's leaves exactly, without splitting the leaves that span a gap
// (split_wide_leaves): what that rule costs.
void BM_CellTreeNanoflannLeaves(benchmark::State& state) {
  const PointCloud& cloud = prepared(size_t(state.range(0)), 0).cloud;
  for (auto _ : state) benchmark::DoNotOptimize(build_cell_tree(cloud, cell_leaf_size(0, cloud.size()), true, false));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(cloud.size()));
}

// As the pipeline builds them: leaves longer than half their tube's radius
// split too (cells/skeleton_regions.h, longest_cell_by_radius). The knot's
// cloud is dense for its tube, so this costs the nearest-bone queries.
void BM_CellTreeByRadius(benchmark::State& state) {
  Prepared& p = prepared(size_t(state.range(0)), 0);
  for (auto _ : state)
    benchmark::DoNotOptimize(build_cell_tree(p.cloud, cell_leaf_size(0, p.cloud.size()), true, true,
                                             longest_cell_by_radius(p.setup.initial.skeleton)));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.cloud.size()));
}

void BM_Radius(benchmark::State& state) {
  Prepared& p = prepared(size_t(state.range(0)), 0);
  for (auto _ : state) benchmark::DoNotOptimize(assign_points_to_bones(p.graph, p.cloud, "knot"));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.cloud.size()));
}

// The skeleton from the cloud alone (issue 15: 400,000 points in at most 1 s).
void BM_ExtractSkeleton(benchmark::State& state) {
  Prepared& p = prepared(size_t(state.range(0)), 0);
  for (auto _ : state) benchmark::DoNotOptimize(extract_skeleton(p.cloud, "knot"));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.cloud.size()));
}

void BM_InitialMesh(benchmark::State& state) {
  Prepared& p = prepared(kPaperPoints, 0);
  InitialMeshOptions options;
  options.target_vertices = size_t(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(build_initial_mesh(p.graph, p.setup.bones, p.cloud, options, "knot"));
}

void BM_Refinement(benchmark::State& state) {
  Prepared& p = prepared(kPaperPoints, 0);
  InitialMeshOptions options;
  options.stage = ConstructionStage::kExtruded;
  QuadMesh rough = build_initial_mesh(p.graph, p.setup.bones, p.cloud, options, "knot").mesh;
  for (auto _ : state) {
    QuadMesh mesh = rough;
    refine_catmull_clark(mesh, int(state.range(0)));
    benchmark::DoNotOptimize(mesh.n_vertices());
  }
}

std::unique_ptr<EvolutionBackend> backend_for(int kind) {
  if (kind == 0) return std::make_unique<SerialBackend>();
#ifdef MCQUAD_WITH_OPENCL
  return std::make_unique<OpenCLBackend>(select_device(""));
#else
  return nullptr;
#endif
}

//! One iteration's step (rays, samples, move, normals), per backend;
//! items are vertex-rays.
void BM_Step(benchmark::State& state) {
  Prepared& p = prepared(size_t(state.range(1)), size_t(state.range(2)));
  auto backend = backend_for(int(state.range(0)));
  if (!backend) return state.SkipWithError("no OpenCL in this build");
  backend->load(p.setup.cells, p.setup.arrays, p.setup.regions);
  unsigned iteration = 0;
  for (auto _ : state) {
    backend->step(make_step_params(p.parameters, iteration++));
    backend->finish();
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.setup.arrays.vertex_count()) *
                          (p.parameters.cones * p.parameters.generators + 1));
  state.SetLabel(backend->name() + ", " + std::to_string(p.setup.arrays.vertex_count()) + " vertices");
}

void BM_ErrorLevel(benchmark::State& state) {
  Prepared& p = prepared(size_t(state.range(1)), size_t(state.range(2)));
  auto backend = backend_for(int(state.range(0)));
  if (!backend) return state.SkipWithError("no OpenCL in this build");
  backend->load(p.setup.cells, p.setup.arrays, p.setup.regions);
  for (auto _ : state) benchmark::DoNotOptimize(backend->error_level());
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.setup.arrays.vertex_count()));
  state.SetLabel(backend->name());
}

//! Robust mode's crossing guard after one step on the knot's mesh (the
//! first step, where every vertex moves furthest); items are faces.
void BM_CrossingGuard(benchmark::State& state) {
  Prepared& p = prepared(kPaperPoints, size_t(state.range(0)));
  SerialBackend backend;
  backend.load(p.setup.cells, p.setup.arrays, p.setup.regions);
  backend.step(make_step_params(p.parameters, 0));
  const std::vector<float> moved = backend.positions();
  CrossingGuard guard(p.setup.arrays);
  for (auto _ : state) {
    std::vector<float> after = moved;
    benchmark::DoNotOptimize(guard.apply(p.setup.arrays.positions, after));
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(p.setup.arrays.face_count()));
  state.SetLabel(std::to_string(p.setup.arrays.face_count()) + " faces");
}

void BM_Metrics(benchmark::State& state) {
  Prepared& p = prepared(kPaperPoints, 0);
  for (auto _ : state)
    benchmark::DoNotOptimize(measure_quality(p.setup.initial.mesh, p.cloud, p.setup.cells, &p.graph));
}

void BM_WriteMesh(benchmark::State& state) {
  Prepared& p = prepared(kPaperPoints, 0);
  std::string path = bench_dir() + "/written.ply";
  for (auto _ : state) write_mesh(path, p.setup.initial.mesh);
}

}  // namespace

BENCHMARK(BM_ReadPly)->Arg(100000)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SortSpatially)->Arg(100000)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CellTree)->Arg(100000)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CellTreeNanoflannLeaves)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CellTreeByRadius)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Radius)->Arg(100000)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ExtractSkeleton)->Arg(100000)->Arg(413696)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_InitialMesh)->Arg(0)->Arg(30000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Refinement)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond);
// Backend (0 serial, 1 OpenCL) x cloud points x mesh vertices (0 = default resolution).
// Steps 1..5 from the initial mesh, every run alike; wall time, since the
// OpenCL backend works on other threads.
BENCHMARK(BM_Step)
    ->ArgsProduct({{0, 1}, {413696}, {0, 30000, 120000}})
    ->ArgsProduct({{0, 1}, {100000, 1000000}, {0}})
    ->Iterations(5)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ErrorLevel)->ArgsProduct({{0, 1}, {413696}, {0, 30000}})->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CrossingGuard)->Arg(0)->Arg(30000)->Arg(120000)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Metrics)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WriteMesh)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
