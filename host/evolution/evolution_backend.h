#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cells/cell_tree.h"
#include "cells/skeleton_regions.h"
#include "core/shared_math.h"
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
};

enum class BackendKind { kAuto, kSerial, kOpenCL };

}  // namespace mcquad
