#include "opencl/opencl_backend.h"

#include <stdexcept>
#include <type_traits>

#include "core/errors.h"
#include "opencl/program_cache.h"

namespace mcquad {
namespace {

//! Global size rounded up to a multiple of the work-group size.
cl::NDRange global_range(size_t items, size_t group) { return cl::NDRange((items + group - 1) / group * group); }
constexpr size_t kGroupSize = 64;

}  // namespace

OpenCLBackend::OpenCLBackend(const DeviceInfo& device) : device_(device) {
  try {
    context_ = cl::Context(device_.device);
    queue_ = cl::CommandQueue(context_, device_.device);
    program_ = mcquad_program(context_, device_.device);
    evolve_kernel_ = cl::Kernel(program_, "evolve_vertices");
    normals_kernel_ = cl::Kernel(program_, "update_normals");
    errors_kernel_ = cl::Kernel(program_, "vertex_errors");
    reduce_kernel_ = cl::Kernel(program_, "reduce_sum");
    relax_kernel_ = cl::Kernel(program_, "relax_tangentially");
    if (has_double_precision(device_.device)) {
      guard_program_ = guard_program(context_, device_.device);
      guard_pairs_kernel_ = cl::Kernel(guard_program_, "guard_test_pairs");
      guard_faces_kernel_ = cl::Kernel(guard_program_, "guard_test_faces");
      guard_folds_kernel_ = cl::Kernel(guard_program_, "guard_test_folds");
      guard_moved_kernel_ = cl::Kernel(guard_program_, "guard_test_moved");
      guard_raise_kernel_ = cl::Kernel(guard_program_, "guard_raise_floors");
    }
  } catch (const cl::Error& e) {
    fail("setting up", e);
  }
}

void OpenCLBackend::fail(const char* operation, const cl::Error& error) const {
  throw DeviceError("OpenCL device " + device_.name + ": " + operation + " failed in " + error.what() + " (" +
                    cl_error_name(error.err()) + ")");
}

template <typename T>
DeviceArray<T> OpenCLBackend::upload(const std::vector<T>& data, cl_mem_flags flags) {
  // A CPU device reads host memory anyway: read-only arrays are used in
  // place (the cells and mesh outlive the backend, as for the serial one)
  // instead of being copied, which saves a copy of the cloud.
  if (device_.type == "CPU" && flags == CL_MEM_READ_ONLY && !data.empty())
    return DeviceArray<T>::in_place(context_, data);
  DeviceArray<T> array(context_, data.size(), flags);
  array.write(queue_, data, false);
  return array;
}

void OpenCLBackend::load(const CellTree& cells, const MeshArrays& mesh, const SkeletonRegions& regions) {
  try {
    vertex_count_ = uint32_t(mesh.vertex_count());
    guard_loaded_ = false;  // a new mesh: the guard's arrays come with the next load_guard
    node_bounds_ = upload(cells.node_bounds);
    bounds_inset_ = cells.bounds_inset;
    node_children_ = upload(cells.node_children);
    cell_offsets_ = upload(cells.cell_offsets);
    points_ = upload(cells.points);
    cell_centroids_ = upload(cells.cell_centroids);
    cell_normals_ = upload(cells.cell_normals);
    cell_facing_ = upload(cells.cell_facing);
    faces_ = upload(mesh.faces);
    vertex_face_offsets_ = upload(mesh.vertex_face_offsets);
    vertex_faces_ = upload(mesh.vertex_faces);
    boundary_ = upload(mesh.boundary);
    cell_bones_ = upload(regions.cell_bones);
    vertex_bones_ = upload(regions.vertex_bones);
    vertex_scale_ = upload(regions.vertex_scale);
    visible_offsets_ = upload(regions.visible_offsets);
    visible_bones_ = upload(regions.visible_bones);
    positions_ = upload(mesh.positions, CL_MEM_READ_WRITE);
    initial_positions_ = upload(mesh.positions);
    initial_normals_ = Floats(context_, mesh.positions.size());
    next_positions_ = Floats(context_, mesh.positions.size());
    normals_ = Floats(context_, mesh.positions.size());
    errors_ = Floats(context_, vertex_count_);
    nearest_cells_ = DeviceArray<int32_t>(context_, vertex_count_);
    nearest_cells_.write(queue_, std::vector<int32_t>(vertex_count_, -1));  // blocking: the vector is a temporary
    reduce_group_size_ = std::min<size_t>(256, device_.device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>());
    // Power of two for the tree reduction.
    while (reduce_group_size_ & (reduce_group_size_ - 1)) reduce_group_size_ &= reduce_group_size_ - 1;
    reduce_groups_ = std::min<size_t>(64, (vertex_count_ + reduce_group_size_ - 1) / reduce_group_size_ + 1);
    partial_sums_ = Floats(context_, reduce_groups_);
    total_ = Floats(context_, 1);
    run_normals();
    initial_normals_.copy_from(queue_, normals_);
    queue_.finish();
  } catch (const cl::Error& e) {
    fail("uploading the cells and the mesh", e);
  }
}

void OpenCLBackend::run_normals() {
  set_kernel_args(normals_kernel_, positions_, faces_, vertex_face_offsets_, vertex_faces_, normals_, vertex_count_);
  queue_.enqueueNDRangeKernel(normals_kernel_, cl::NullRange, global_range(vertex_count_, kGroupSize),
                              cl::NDRange(kGroupSize));
}

void OpenCLBackend::step(const device::mcq_step_params& params) {
  try {
    if (guard_loaded_) step_start_.copy_from(queue_, positions_);
    if (params.relaxation > 0.0f) {
      set_kernel_args(relax_kernel_, positions_, normals_, faces_, vertex_face_offsets_, vertex_faces_, boundary_,
                      next_positions_, params.relaxation, vertex_count_);
      queue_.enqueueNDRangeKernel(relax_kernel_, cl::NullRange, global_range(vertex_count_, kGroupSize),
                                  cl::NDRange(kGroupSize));
      swap(positions_, next_positions_);
      run_normals();
    }
    set_kernel_args(evolve_kernel_, positions_, normals_, initial_positions_, initial_normals_, next_positions_, faces_,
                    vertex_face_offsets_, vertex_faces_, boundary_, node_bounds_, node_children_, cell_offsets_,
                    points_, cell_centroids_, cell_normals_, cell_facing_, bounds_inset_, cell_bones_, vertex_bones_,
                    vertex_scale_, visible_offsets_, visible_bones_, params, vertex_count_);
    queue_.enqueueNDRangeKernel(evolve_kernel_, cl::NullRange, global_range(vertex_count_, kGroupSize),
                                cl::NDRange(kGroupSize));
    swap(positions_, next_positions_);
    run_normals();
  } catch (const cl::Error& e) {
    fail("the Monte Carlo step", e);
  }
}

double OpenCLBackend::error_level() {
  try {
    set_kernel_args(errors_kernel_, positions_, node_bounds_, node_children_, cell_offsets_, points_, cell_centroids_,
                    cell_normals_, bounds_inset_, errors_, nearest_cells_, vertex_count_);
    queue_.enqueueNDRangeKernel(errors_kernel_, cl::NullRange, global_range(vertex_count_, kGroupSize),
                                cl::NDRange(kGroupSize));
    set_kernel_args(reduce_kernel_, errors_, partial_sums_, cl::Local(reduce_group_size_ * sizeof(float)),
                    vertex_count_);
    queue_.enqueueNDRangeKernel(reduce_kernel_, cl::NullRange, cl::NDRange(reduce_groups_ * reduce_group_size_),
                                cl::NDRange(reduce_group_size_));
    set_kernel_args(reduce_kernel_, partial_sums_, total_, cl::Local(reduce_group_size_ * sizeof(float)),
                    uint32_t(reduce_groups_));
    queue_.enqueueNDRangeKernel(reduce_kernel_, cl::NullRange, cl::NDRange(reduce_group_size_),
                                cl::NDRange(reduce_group_size_));
    float total = total_.read(queue_)[0];
    return vertex_count_ ? double(total) / vertex_count_ : 0.0;
  } catch (const cl::Error& e) {
    fail("the error level", e);
  }
}

void OpenCLBackend::finish() {
  try {
    queue_.finish();
  } catch (const cl::Error& e) {
    fail("waiting for the device", e);
  }
}

std::vector<float> OpenCLBackend::positions() {
  try {
    return positions_.read(queue_);
  } catch (const cl::Error& e) {
    fail("reading the positions back", e);
  }
}

void OpenCLBackend::set_positions(const std::vector<float>& positions) {
  try {
    if (positions.size() != positions_.size())
      throw std::invalid_argument("set_positions: wrong number of coordinates");
    positions_.write(queue_, positions);
    run_normals();
  } catch (const cl::Error& e) {
    fail("writing the positions", e);
  }
}

void OpenCLBackend::load_guard(const GuardArrays& arrays, bool floors_only) {
  if (!tests_guard()) return;
  try {
    // Written, not used in place: the host's arrays change after this call.
    // A buffer of the right size is written over (the floors, after every
    // host step that held nothing back).
    auto write = [&](auto& device_array, const auto& host) {
      using T = typename std::decay_t<decltype(host)>::value_type;
      if (device_array.size() != host.size()) device_array = DeviceArray<T>(context_, host.size());
      device_array.write(queue_, host);
    };
    write(guard_floors_, arrays.jacobian_floors);
    if (floors_only && guard_loaded_) return;
    write(guard_triangles_, arrays.triangle_corners);
    write(guard_pairs_, arrays.close_pairs);
    write(guard_references_, arrays.references);
    write(guard_fold_pairs_, arrays.fold_pairs);
    write(guard_initial_normals_, arrays.initial_normals);
    guard_move_limit_ = arrays.move_limit;
    if (!guard_loaded_) {
      step_start_ = Floats(context_, positions_.size());
      guard_found_ = Indices(context_, 1);
      guard_loaded_ = true;
    }
  } catch (const cl::Error& e) {
    fail("loading the crossing guard's arrays", e);
  }
}

bool OpenCLBackend::guard_finds_nothing() {
  if (!guard_loaded_) return false;
  try {
    const uint32_t pairs = uint32_t(guard_pairs_.size() / 2), faces = uint32_t(faces_.size() / 4);
    const uint32_t fold_pairs = uint32_t(guard_fold_pairs_.size() / 2);
    guard_found_.write(queue_, std::vector<uint32_t>{0u});
    auto run = [&](cl::Kernel& kernel, uint32_t items) {
      if (items > 0)
        queue_.enqueueNDRangeKernel(kernel, cl::NullRange, global_range(items, kGroupSize), cl::NDRange(kGroupSize));
    };
    set_kernel_args(guard_moved_kernel_, positions_, guard_references_, guard_move_limit_, vertex_count_, guard_found_);
    run(guard_moved_kernel_, vertex_count_);
    set_kernel_args(guard_pairs_kernel_, positions_, guard_triangles_, guard_pairs_, pairs, guard_found_);
    run(guard_pairs_kernel_, pairs);
    set_kernel_args(guard_faces_kernel_, positions_, faces_, guard_initial_normals_, guard_floors_, faces,
                    guard_found_);
    run(guard_faces_kernel_, faces);
    set_kernel_args(guard_folds_kernel_, positions_, faces_, guard_fold_pairs_, fold_pairs, guard_found_);
    run(guard_folds_kernel_, fold_pairs);
    if (guard_found_.read(queue_)[0] != 0u) return false;
    set_kernel_args(guard_raise_kernel_, positions_, faces_, guard_floors_, CrossingGuard::kLeastScaledJacobian, faces);
    run(guard_raise_kernel_, faces);
    return true;
  } catch (const cl::Error& e) {
    fail("the crossing guard's test", e);
  }
}

std::vector<double> OpenCLBackend::guard_floors() {
  try {
    return guard_floors_.read(queue_);
  } catch (const cl::Error& e) {
    fail("reading the Jacobian floors back", e);
  }
}

std::vector<float> OpenCLBackend::positions_before_step() {
  try {
    return step_start_.read(queue_);
  } catch (const cl::Error& e) {
    fail("reading the positions back", e);
  }
}

std::vector<float> OpenCLBackend::normals() {
  try {
    return normals_.read(queue_);
  } catch (const cl::Error& e) {
    fail("reading the normals back", e);
  }
}

std::string cl_error_name(cl_int code) {
  switch (code) {
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE:
      return "CL_DEVICE_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE: out of device memory";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE: buffer larger than the device allows";
    case CL_INVALID_KERNEL_ARGS:
      return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE:
      return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_ARG_SIZE:
      return "CL_INVALID_ARG_SIZE";
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "OpenCL error " + std::to_string(code);
  }
}

}  // namespace mcquad
