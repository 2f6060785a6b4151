#include "evolution/evolve.h"

#include <chrono>
#include <memory>

#include "core/progress.h"
#include "mesh/crossing_guard.h"

namespace mcquad {

// The step parameters cross to the device as one kernel argument: 4-byte
// fields only, so the layout is the same on both sides.
static_assert(sizeof(device::mcq_step_params) == 18 * 4, "mcq_step_params must stay 4-byte fields");

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
  params.curvature_correction = robust && parameters.curvature_correction ? 1u : 0u;
  return params;
}

namespace {

//! Moves the held-back vertices toward the mean of their neighbours within
//! their tangent planes (the relaxation robust mode offers for every vertex,
//! mcq_relaxed_position, here for these only), through the guard again.
//! Where a crease or a merged stem stops them, the next step's moves into
//! it cross less once they are spread out (docs/DESIGN.md).
void relax_held_back(const MeshArrays& mesh, CrossingGuard& guard, const std::vector<uint32_t>& held, float weight,
                     std::vector<float>& positions) {
  std::vector<float> normals(positions.size(), 0.0f), relaxed = positions;
  for (uint32_t v : held)
    device::mcq_store3(normals.data(), v,
                       device::mcq_vertex_normal(positions.data(), mesh.faces.data(), mesh.vertex_face_offsets.data(),
                                                 mesh.vertex_faces.data(), v));
  for (uint32_t v : held)
    device::mcq_store3(relaxed.data(), v,
                       device::mcq_relaxed_position(positions.data(), normals.data(), mesh.faces.data(),
                                                    mesh.vertex_face_offsets.data(), mesh.vertex_faces.data(),
                                                    mesh.boundary.data(), v, weight));
  guard.apply(positions, relaxed);
  positions.swap(relaxed);
}

//! Robust mode's crossing guard on the step just taken from `before`; the
//! backend gets the shortened (and relaxed) positions, and `before` becomes
//! the accepted ones. Returns how many vertices were held back.
size_t guard_step(EvolutionBackend& backend, const MeshArrays& mesh, CrossingGuard& guard, float relaxation,
                  std::vector<float>& before) {
  std::vector<float> after = backend.positions();
  std::vector<uint32_t> held = guard.apply(before, after);
  if (!held.empty() && relaxation > 0.0f) relax_held_back(mesh, guard, held, relaxation, after);
  if (!held.empty()) backend.set_positions(after);
  backend.finish();
  before.swap(after);
  return held.size();
}

}  // namespace

EvolutionResult evolve(EvolutionBackend& backend, const MeshArrays& mesh, const EvolutionParameters& parameters,
                       const IterationCallback& after_iteration, unsigned first_iteration) {
  using Clock = std::chrono::steady_clock;
  EvolutionResult result;
  result.initial_error_level = backend.error_level();
  result.stop_reason = "iteration limit";
  double previous = result.initial_error_level;
  Progress progress("evolving", parameters.iterations);
  bool guard = parameters.mode == EvolutionParameters::Mode::kRobust && parameters.crossing_guard;
  // The guard compares each step with the positions before it; they stay on
  // the host between steps (12 bytes a vertex each way per iteration).
  std::vector<float> before = guard ? backend.positions() : std::vector<float>();
  std::unique_ptr<CrossingGuard> crossing_guard = guard ? std::make_unique<CrossingGuard>(mesh) : nullptr;
  for (unsigned i = 0; i < parameters.iterations; ++i) {
    auto start = Clock::now();
    backend.step(make_step_params(parameters, first_iteration + i));
    backend.finish();
    IterationRecord record;
    record.iteration = first_iteration + i + 1;
    auto stepped = Clock::now();
    if (crossing_guard)
      record.held_back_vertices =
          guard_step(backend, mesh, *crossing_guard, float(parameters.held_back_relaxation), before);
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

}  // namespace mcquad
