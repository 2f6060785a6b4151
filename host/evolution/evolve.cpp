#include "evolution/evolve.h"

#include <chrono>
#include <memory>
#include <tuple>

#include "core/progress.h"
#include "evolution/guarded_steps.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {

// The step parameters cross to the device as one kernel argument: 4-byte
// fields only, so the layout is the same on both sides.
static_assert(sizeof(device::mcq_step_params) == 19 * 4, "mcq_step_params must stay 4-byte fields");

device::mcq_step_params make_step_params(const EvolutionParameters& parameters, unsigned iteration) {
  device::mcq_step_params params;
  params.cones = parameters.cones;
  params.generators = parameters.generators;
  params.samples = parameters.samples;
  params.seed = parameters.seed;
  params.iteration = iteration;
  params.alpha_max = float(parameters.alpha_max);
  params.epsilon = float(parameters.epsilon);
  // The paper: epsilon "determines the maximal distance of the acceptable
  // point cells" -- rays look no further than that.
  params.reach = float(parameters.epsilon);
  bool robust = parameters.mode == EvolutionParameters::Mode::kRobust;
  params.fold_guard = robust ? 1u : 0u;
  params.relaxation = robust ? float(parameters.relaxation) : 0.0f;
  params.mean_projection = robust && parameters.mean_projection ? 1u : 0u;
  params.fill_holes = robust && parameters.fill_holes ? 1u : 0u;
  params.own_cells = robust && parameters.own_cells ? 1u : 0u;
  params.local_epsilon = robust && parameters.local_epsilon ? 1u : 0u;
  params.band = robust ? float(parameters.hit_band * parameters.epsilon) : 0.0f;
  params.facing_cells = robust && parameters.facing_cells ? 1u : 0u;
  params.min_facing = float(parameters.min_facing);
  params.curvature_correction = !robust || !parameters.curvature_correction ? 0u
                                : parameters.curvature_at_start             ? 2u
                                                                            : 1u;
  params.nearest_plane = robust && parameters.nearest_plane ? 1u : 0u;
  return params;
}

EvolutionResult evolve(EvolutionBackend& backend, const MeshArrays& mesh, const EvolutionParameters& parameters,
                       const IterationCallback& after_iteration, unsigned first_iteration) {
  using Clock = std::chrono::steady_clock;
  EvolutionResult result;
  result.initial_error_level = backend.error_level();
  result.stop_reason = "iteration limit";
  double previous = result.initial_error_level;
  Progress progress("evolving", parameters.iterations);
  bool guard = parameters.mode == EvolutionParameters::Mode::kRobust && parameters.crossing_guard;
  // The guard compares each step with the positions before it.
  std::unique_ptr<GuardedSteps> crossing_guard =
      guard ? std::make_unique<GuardedSteps>(backend, mesh, float(parameters.held_back_relaxation),
                                             parameters.guard_test_on_backend)
            : nullptr;
  for (unsigned i = 0; i < parameters.iterations; ++i) {
    auto start = Clock::now();
    backend.step(make_step_params(parameters, first_iteration + i));
    backend.finish();
    IterationRecord record;
    record.iteration = first_iteration + i + 1;
    auto stepped = Clock::now();
    if (crossing_guard) std::tie(record.held_back_vertices, record.guard_on_host) = crossing_guard->guard();
    auto guarded = Clock::now();
    record.error_level = backend.error_level();
    auto end = Clock::now();
    record.step_seconds = std::chrono::duration<double>(stepped - start).count();
    record.guard_seconds = std::chrono::duration<double>(guarded - stepped).count();
    record.error_seconds = std::chrono::duration<double>(end - guarded).count();
    record.seconds = record.step_seconds + record.guard_seconds + record.error_seconds;
    result.iterations.push_back(record);
    progress.update(i + 1);
    if (after_iteration) after_iteration(record, backend);
    if (parameters.tolerance > 0 && previous - record.error_level < parameters.tolerance * previous) {
      result.stop_reason = "error level improved by less than the tolerance";
      break;
    }
    previous = record.error_level;
  }
  result.positions = backend.positions();
  return result;
}

void settle_onto_cloud(EvolutionBackend& backend, const MeshArrays& start, const EvolutionParameters& parameters,
                       QuadMesh& mesh, unsigned first_iteration, unsigned iterations) {
  backend.set_positions(mesh_positions(mesh));
  EvolutionParameters settle = parameters;
  settle.iterations = iterations;
  settle.tolerance = 0;
  set_positions(mesh, evolve(backend, start, settle, {}, first_iteration).positions);
}

}  // namespace mcquad
