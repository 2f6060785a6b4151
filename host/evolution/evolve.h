#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/quad_mesh.h"
#include "evolution/evolution_backend.h"
#include "evolution/evolution_parameters.h"

namespace mcquad {

struct IterationRecord {
  unsigned iteration = 0;         //!< 1-based
  double error_level = 0;         //!< the paper's e-bar after this iteration
  double seconds = 0;             //!< wall time of the step, normals, crossing guard and error level
  double step_seconds = 0;        //!< of which the step and the normals
  double guard_seconds = 0;       //!< of which the crossing guard (robust mode)
  double error_seconds = 0;       //!< of which the error level
  size_t held_back_vertices = 0;  //!< vertices whose step the crossing guard shortened
  //! Whether the crossing guard ran on the host (the positions came back);
  //! false where the backend found nothing for it to hold back.
  bool guard_on_host = false;
};

struct EvolutionResult {
  double initial_error_level = 0;
  std::vector<IterationRecord> iterations;
  std::string stop_reason;
  std::vector<float> positions;
};

//! Called after each iteration with its record; snapshots read positions
//! from the backend here (the only time the mesh leaves the device early).
using IterationCallback = std::function<void(const IterationRecord&, EvolutionBackend&)>;

//! Step parameters of iteration `iteration` (0-based) for the shared code.
device::mcq_step_params make_step_params(const EvolutionParameters& parameters, unsigned iteration);

//! Runs the evolution on a loaded backend (`mesh` is what it was loaded
//! with): up to `iterations` Jacobi steps, each followed in robust mode by the
//! crossing guard, stopping early when the error level improves by less than `tolerance`
//! (relative) from one iteration to the next. Iterations are numbered
//! (and seeded) from `first_iteration` on, so an evolution that goes on
//! draws new rays.
EvolutionResult evolve(EvolutionBackend& backend, const MeshArrays& mesh, const EvolutionParameters& parameters,
                       const IterationCallback& after_iteration = {}, unsigned first_iteration = 0);

//! `iterations` more steps (no early stop) from `mesh`'s positions on the
//! backend loaded with `start`, numbered from `first_iteration`; the mesh
//! takes the result. After a move made outside the evolution (a smoothing,
//! a push, a reach), so that what it lifted off the cloud settles back.
void settle_onto_cloud(EvolutionBackend& backend, const MeshArrays& start, const EvolutionParameters& parameters,
                       QuadMesh& mesh, unsigned first_iteration, unsigned iterations);

}  // namespace mcquad
