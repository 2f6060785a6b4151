#include "evolution/guarded_steps.h"

#include "core/shared_math.h"

namespace mcquad {
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

GuardedSteps::GuardedSteps(EvolutionBackend& backend, const MeshArrays& mesh, float relaxation, bool test_on_backend)
    : backend_(backend),
      mesh_(mesh),
      guard_(mesh),
      relaxation_(relaxation),
      test_on_backend_(test_on_backend && backend.tests_guard()),
      before_(backend.positions()) {
  if (test_on_backend_) load(false);
}

std::pair<size_t, bool> GuardedSteps::guard() {
  // Tested on the backend only after a step the host guard let through
  // whole: where it holds vertices back step after step (the junctions of
  // most generated shapes), the test would find something every time.
  const bool tested = test_on_backend_ && held_last_step_ == 0 && guard_.knows_no_defects();
  if (tested && backend_.guard_finds_nothing()) {
    before_current_ = false;
    stale_steps_ = 0;
    return {0, false};
  }
  if (!before_current_) {
    before_ = backend_.positions_before_step();
    guard_.resume(before_, backend_.guard_floors());
    before_current_ = true;
  }
  const size_t version = guard_.close_pairs_version();
  held_last_step_ = guard_step(backend_, mesh_, guard_, relaxation_, before_);
  // A step the backend sent here in which the host found nothing to hold
  // back but had to make its close pairs again: the steps outrun the list.
  // Twice in a row, and the list is made with twice the gap.
  const bool outrun = tested && held_last_step_ == 0 && guard_.close_pairs_version() != version;
  stale_steps_ = outrun ? stale_steps_ + 1 : 0;
  if (stale_steps_ >= kOutrunStepsBeforeWidening && guard_.widen_close_pairs()) stale_steps_ = 0;
  if (test_on_backend_ && held_last_step_ == 0) load(guard_.close_pairs_version() == loaded_version_);
  return {held_last_step_, true};
}

void GuardedSteps::load(bool floors_only) {
  if (floors_only) {
    GuardArrays floors;
    floors.jacobian_floors = guard_.jacobian_floors();
    backend_.load_guard(floors, true);
    return;
  }
  backend_.load_guard(guard_.device_arrays(), false);
  loaded_version_ = guard_.close_pairs_version();
}

}  // namespace mcquad
