#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cells/cell_tree.h"
#include "cells/skeleton_regions.h"
#include "core/shared_math.h"
#include "mesh/crossing_guard.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {

//! One interface for the two ways of running the evolution: the serial C++
//! reference and the OpenCL kernels. Both read the same flattened arrays and
//! run the same per-vertex code (kernels/shared/), so they can be compared.
class EvolutionBackend {
 public:
  virtual ~EvolutionBackend() = default;

  //! "serial" or "opencl".
  virtual std::string name() const = 0;
  //! Where it runs, for reports ("host CPU", an OpenCL device's name).
  virtual std::string device_name() const = 0;

  //! Takes the cells, the mesh and their skeleton regions (uploading them
  //! where that applies) and computes the initial normals. All three must
  //! outlive the backend: the serial one reads them, and the OpenCL one uses
  //! them in place on a CPU device.
  virtual void load(const CellTree& cells, const MeshArrays& mesh, const SkeletonRegions& regions) = 0;
  //! One Jacobi step of every vertex, then the normals of the new positions.
  virtual void step(const device::mcq_step_params& params) = 0;
  //! The paper's error level: mean distance of the vertices to the plane of
  //! the cell holding their nearest cloud point.
  virtual double error_level() = 0;
  //! Waits until queued device work is done (for timing); no-op on the host.
  virtual void finish() {}
  //! Current vertex positions (3 floats each), copied back where needed.
  virtual std::vector<float> positions() = 0;
  //! Current vertex normals (3 floats each).
  virtual std::vector<float> normals() = 0;
  //! Replaces the vertex positions (same count) and recomputes the normals.
  virtual void set_positions(const std::vector<float>& positions) = 0;

  // Robust mode's crossing guard tested where the positions are, so that
  // they come back to the host only when the guard holds something back
  // (kernels/guard.cl). The serial backend's positions are on the host
  // already; it has no such test.

  //! Whether this backend can test a step for the guard.
  virtual bool tests_guard() const { return false; }
  //! Takes what the test needs; with `floors_only`, only the Jacobian floors
  //! have changed since the last call.
  virtual void load_guard(const GuardArrays& /*arrays*/, bool /*floors_only*/) {}
  //! Whether the last step left none of the defects the guard holds back
  //! (CrossingGuard::apply would change nothing); if so, the Jacobian floors
  //! rise as apply() raises them. False where the backend cannot tell.
  virtual bool guard_finds_nothing() { return false; }
  //! The Jacobian floors as the backend holds them (after load_guard).
  virtual std::vector<double> guard_floors() { return {}; }
  //! The positions the last step started from (after load_guard).
  virtual std::vector<float> positions_before_step() { return {}; }
};

enum class BackendKind { kAuto, kSerial, kOpenCL };

}  // namespace mcquad
