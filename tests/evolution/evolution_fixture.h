#pragma once

// What the evolution tests share: a generated shape prepared for evolving,
// and the OpenCL backend where one is found.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <tuple>

#include "evolution/evolution_backend.h"
#include "evolution/evolve.h"
#include "evolution/serial_backend.h"
#include "evolution/turned_face_smoothing.h"
#include "helpers.h"
#include "metrics/surface_distance.h"
#include "pipeline/fit.h"
#include "pipeline/prepare.h"
#ifdef MCQUAD_WITH_OPENCL
#include "opencl/device_selection.h"
#include "opencl/opencl_backend.h"
#include "opencl/program_cache.h"
#include "embedded_test_kernels.h"  // generated from kernels/test_kernels.cl
#endif

namespace mcquad::test {

//! A generated shape with everything the evolution starts from.
struct Fixture {
  GeneratedShape shape;
  SkeletonGraph graph;
  EvolutionSetup setup;
  const InitialMesh& initial = setup.initial;
  const CellTree& cells = setup.cells;
  const MeshArrays& arrays = setup.arrays;
  const SkeletonRegions& regions = setup.regions;
  EvolutionParameters parameters;
  double radius = setup.median_radius;

  explicit Fixture(const std::string& name, size_t points, ShapeOptions options = {},
                   const InitialMeshOptions& initial_options = {})
      : shape(test::small_shape(name, points, options)),
        graph(build_skeleton_graph(shape.skeleton, name)),
        setup(prepare_evolution(graph, shape.cloud, initial_options, FitOptions().leaf_size, name)) {
    parameters.epsilon = automatic_epsilon(radius);
  }

  std::vector<double> true_surface_distances(const std::vector<float>& positions) const {
    std::vector<double> out;
    for (size_t v = 0; v < positions.size() / 3; ++v)
      out.push_back(std::abs(shape.surface.signed_distance(
          Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]))));
    return out;
  }

  //! Vertex v's distance to the true surface relative to the local tube radius.
  double relative_surface_distance(const std::vector<float>& positions, size_t v) const {
    Eigen::Vector3d x(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    return std::abs(shape.surface.signed_distance(x)) /
           shape.surface.capsules()[shape.surface.nearest_capsule(x)].radius;
  }

  //! Distances to the true surface relative to the local tube radius.
  DistanceSummary relative_surface_distances(const std::vector<float>& positions) const {
    std::vector<double> relative;
    for (size_t v = 0; v < positions.size() / 3; ++v) relative.push_back(relative_surface_distance(positions, v));
    return summarize_distances(relative);
  }

  //! Final positions of an evolution on `backend` in `mode`, the rest as in `parameters`.
  std::vector<float> evolve_on(EvolutionBackend& backend, EvolutionParameters::Mode mode) const {
    backend.load(cells, arrays, regions);
    EvolutionParameters p = parameters;
    p.mode = mode;
    return evolve(backend, arrays, p).positions;
  }

  //! What a fit leaves: evolve_on, then in robust mode the smoothing of the
  //! faces turned against the scan's normals, as pipeline/fit.cpp runs it.
  std::vector<float> fit_on(EvolutionBackend& backend, EvolutionParameters::Mode mode) const {
    std::vector<float> positions = evolve_on(backend, mode);
    if (mode != EvolutionParameters::Mode::kRobust) return positions;
    QuadMesh mesh = initial.mesh;
    set_positions(mesh, positions);
    OrientedSample normals = oriented_sample(shape.cloud);
    ScanOrientation scan(normals);
    EvolutionParameters p = parameters;
    p.mode = mode;
    turn_faces_out(backend, arrays, p, scan, mesh, p.iterations);
    return mesh_positions(mesh);
  }

  std::vector<float> evolve_serially(EvolutionParameters::Mode mode) const {
    SerialBackend backend;
    return evolve_on(backend, mode);
  }
};

#ifdef MCQUAD_WITH_OPENCL
inline std::unique_ptr<OpenCLBackend> opencl_or_skip() {
  auto devices = list_devices();
  if (devices.empty()) {
    if (opencl_required()) ADD_FAILURE() << "no OpenCL device, and CI requires one (install pocl-opencl-icd)";
    return nullptr;
  }
  return std::make_unique<OpenCLBackend>(select_device(""));
}

//! A context, queue and program of the shared kernel code with the tests'
//! hooks (kernels/test_kernels.cl), on the device mcquad would choose.
struct TestProgram {
  cl::Context context;
  cl::CommandQueue queue;
  cl::Program program;
};
inline TestProgram test_program() {
  DeviceInfo device = select_device("");
  TestProgram t;
  t.context = cl::Context(device.device);
  t.queue = cl::CommandQueue(t.context, device.device);
  t.program = build_program(t.context, device.device, shared_kernel_source() + embedded::test_kernels_cl);
  return t;
}

//! Vertices whose positions differ by more than `tolerance` in a coordinate.
inline size_t count_differing(const std::vector<float>& a, const std::vector<float>& b, float tolerance) {
  size_t differing = 0;
  for (size_t v = 0; v < a.size() / 3; ++v) {
    float d = 0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(a[3 * v + k] - b[3 * v + k]));
    differing += d > tolerance;
  }
  return differing;
}

#endif

//! The backends behaviour tests run on (TEST_P over these): the serial path,
//! and OpenCL in builds that have it.
inline std::vector<BackendKind> backend_kinds() {
#ifdef MCQUAD_WITH_OPENCL
  return {BackendKind::kSerial, BackendKind::kOpenCL};
#else
  return {BackendKind::kSerial};
#endif
}

inline std::string backend_label(const testing::TestParamInfo<BackendKind>& info) {
  return info.param == BackendKind::kSerial ? "Serial" : "OpenCL";
}

//! A case-by-backend test's name: the case's label, then _serial or _opencl.
template <class Case>
std::string case_and_backend_label(const testing::TestParamInfo<std::tuple<Case, BackendKind>>& info) {
  return std::string(std::get<0>(info.param).label) +
         (std::get<1>(info.param) == BackendKind::kSerial ? "_serial" : "_opencl");
}

//! A backend of `kind`; null where OpenCL has no device (a failure where CI
//! requires one: the test then returns, else it skips).
inline std::unique_ptr<EvolutionBackend> backend_of(BackendKind kind) {
  if (kind == BackendKind::kSerial) return std::make_unique<SerialBackend>();
#ifdef MCQUAD_WITH_OPENCL
  return opencl_or_skip();
#else
  return nullptr;
#endif
}

#define REQUIRE_BACKEND(backend, kind)                                          \
  auto backend = ::mcquad::test::backend_of(kind);                              \
  if (!backend) {                                                               \
    if (!::mcquad::test::opencl_required()) GTEST_SKIP() << "no OpenCL device"; \
    return;                                                                     \
  }

#ifdef MCQUAD_WITH_OPENCL
#define REQUIRE_OPENCL(backend)                                                 \
  auto backend = ::mcquad::test::opencl_or_skip();                              \
  if (!backend) {                                                               \
    if (!::mcquad::test::opencl_required()) GTEST_SKIP() << "no OpenCL device"; \
    return;                                                                     \
  }
#endif

}  // namespace mcquad::test
