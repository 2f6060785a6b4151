#pragma once

#include "evolution/evolution_backend.h"
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

  //! Queue and program for kernel unit tests.
  cl::CommandQueue& queue() { return queue_; }
  cl::Context& context() { return context_; }
  cl::Program& program() { return program_; }

 private:
  template <typename T>
  cl::Buffer upload(const std::vector<T>& data, cl_mem_flags flags = CL_MEM_READ_ONLY);
  void run_normals();
  //! Rethrows cl::Error as DeviceError naming the device and the operation.
  [[noreturn]] void fail(const char* operation, const cl::Error& error) const;

  DeviceInfo device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  cl::Program program_;
  cl::Kernel evolve_kernel_, normals_kernel_, errors_kernel_, reduce_kernel_, relax_kernel_;
  cl::Buffer node_bounds_, node_children_, cell_offsets_, points_, cell_centroids_, cell_normals_;
  cl::Buffer faces_, vertex_face_offsets_, vertex_faces_, boundary_;
  cl::Buffer positions_, next_positions_, normals_, errors_, partial_sums_, total_;
  cl::Buffer initial_positions_, initial_normals_;  //!< where the evolution started, for hole filling
  cl::Buffer cell_bones_, vertex_bones_, vertex_scale_, visible_offsets_, visible_bones_;  //!< skeleton regions
  uint32_t vertex_count_ = 0;
  size_t reduce_groups_ = 0, reduce_group_size_ = 0;
};

}  // namespace mcquad
