#include "evolution/evolve.h"

#include <chrono>

#include "core/progress.h"

namespace mcquad {

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
  return params;
}

EvolutionResult evolve(EvolutionBackend& backend, const EvolutionParameters& parameters,
                       const IterationCallback& after_iteration) {
  using Clock = std::chrono::steady_clock;
  EvolutionResult result;
  result.initial_error_level = backend.error_level();
  result.stop_reason = "iteration limit";
  double previous = result.initial_error_level;
  Progress progress("evolving", parameters.iterations);
  for (unsigned i = 0; i < parameters.iterations; ++i) {
    auto start = Clock::now();
    backend.step(make_step_params(parameters, i));
    backend.finish();
    auto stepped = Clock::now();
    IterationRecord record;
    record.iteration = i + 1;
    record.error_level = backend.error_level();
    auto end = Clock::now();
    record.step_seconds = std::chrono::duration<double>(stepped - start).count();
    record.error_seconds = std::chrono::duration<double>(end - stepped).count();
    record.seconds = record.step_seconds + record.error_seconds;
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
