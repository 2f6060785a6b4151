#pragma once

#include "evolution/evolution_backend.h"
#include "opencl/device_array.h"
#include "opencl/device_selection.h"

namespace mcquad {

//! Runs the whole evolution on an OpenCL device: the cells and the mesh are
//! uploaded once; each iteration runs evolve_vertices, update_normals,
//! vertex_errors and a two-stage reduction, and only the error level (one
//! float) comes back. Positions come back on request (end, snapshots).
class OpenCLBackend : public EvolutionBackend {
 public:
  explicit OpenCLBackend(const DeviceInfo& device);
  std::string name() const override { return "opencl"; }
  std::string device_name() const override { return device_.name + " (" + device_.platform + ")"; }
  void load(const CellTree& cells, const MeshArrays& mesh, const SkeletonRegions& regions) override;
  void step(const device::mcq_step_params& params) override;
  double error_level() override;
  void finish() override;
  std::vector<float> positions() override;
  std::vector<float> normals() override;
  void set_positions(const std::vector<float>& positions) override;
  bool tests_guard() const override { return bool(guard_program_()); }
  void load_guard(const GuardArrays& arrays, bool floors_only) override;
  bool guard_finds_nothing() override;
  std::vector<double> guard_floors() override;
  std::vector<float> positions_before_step() override;

 private:
  using Floats = DeviceArray<float>;
  using Indices = DeviceArray<uint32_t>;
  //! A read-only array of the host's, used in place on a CPU device.
  template <typename T>
  DeviceArray<T> upload(const std::vector<T>& data, cl_mem_flags flags = CL_MEM_READ_ONLY);
  void run_normals();
  //! Rethrows cl::Error as DeviceError naming the device and the operation.
  [[noreturn]] void fail(const char* operation, const cl::Error& error) const;

  DeviceInfo device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  cl::Program program_;
  cl::Kernel evolve_kernel_, normals_kernel_, errors_kernel_, reduce_kernel_, relax_kernel_;
  Floats node_bounds_, points_, cell_centroids_, cell_normals_, cell_facing_;
  DeviceArray<int32_t> node_children_;
  DeviceArray<int32_t> nearest_cells_;  //!< each vertex's nearest cell at the last error level, a guess for the next
  Indices cell_offsets_, faces_, vertex_face_offsets_, vertex_faces_, boundary_;
  Floats positions_, next_positions_, normals_, errors_, partial_sums_, total_;
  Floats initial_positions_, initial_normals_;  //!< where the evolution started, for hole filling
  Indices cell_bones_, vertex_bones_, visible_offsets_, visible_bones_;  //!< skeleton regions
  Floats vertex_scale_;
  // The crossing guard's test (kernels/guard.cl), on devices with double precision.
  cl::Program guard_program_;
  cl::Kernel guard_pairs_kernel_, guard_faces_kernel_, guard_folds_kernel_, guard_moved_kernel_, guard_raise_kernel_;
  Indices guard_triangles_, guard_pairs_, guard_fold_pairs_, guard_found_;
  Floats guard_references_, guard_initial_normals_, step_start_;
  DeviceArray<double> guard_floors_;
  double guard_move_limit_ = 0;
  bool guard_loaded_ = false;
  float bounds_inset_ = 0;  //!< CellTree::bounds_inset
  uint32_t vertex_count_ = 0;
  size_t reduce_groups_ = 0, reduce_group_size_ = 0;
};

}  // namespace mcquad
