#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "evolution/evolution_backend.h"
#include "mesh/crossing_guard.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {

//! Robust mode's crossing guard (mesh/crossing_guard.h) after each step of
//! an evolution. Where the backend can test a step for the guard
//! (EvolutionBackend::tests_guard: OpenCL with double precision), it does:
//! as long as the mesh has no crossing or fold and the backend finds none
//! of the guard's defects after a step, the host guard would change
//! nothing, and the positions stay on the device (issue 18). After a step
//! in which the host guard held vertices back, the next goes to the host
//! untested (where it holds some back at every step, a test would only
//! cost). Where the steps keep outrunning the guard's list of close pairs
//! (the positions must come back to make it again), the list is made with a
//! wider gap (CrossingGuard::widen_close_pairs). Otherwise the
//! host guard runs as it does without the test, from the positions the step
//! started from. The positions come out the same either way, bit for bit.
class GuardedSteps {
 public:
  //! `backend` holds `mesh` (loaded, at its starting positions); both must
  //! outlive this. `relaxation`: EvolutionParameters::held_back_relaxation.
  //! `test_on_backend`: EvolutionParameters::guard_test_on_backend.
  GuardedSteps(EvolutionBackend& backend, const MeshArrays& mesh, float relaxation, bool test_on_backend);

  //! After a step: how many vertices the guard held back, and whether the
  //! host ran it (the positions came back).
  std::pair<size_t, bool> guard();

 private:
  //! Gives the backend what its test needs, or only the Jacobian floors.
  void load(bool floors_only);

  EvolutionBackend& backend_;
  const MeshArrays& mesh_;
  CrossingGuard guard_;
  float relaxation_;
  bool test_on_backend_;
  std::vector<float> before_;   //!< the positions last accepted, while before_current_
  bool before_current_ = true;  //!< false after steps the backend accepted alone
  size_t loaded_version_ = 0;   //!< CrossingGuard::close_pairs_version the backend holds
  size_t held_last_step_ = 0;   //!< vertices the host guard held back at its last step
  int stale_steps_ = 0;         //!< steps in a row the close pairs went stale with nothing held back
  static constexpr int kOutrunStepsBeforeWidening = 2;
};

}  // namespace mcquad
