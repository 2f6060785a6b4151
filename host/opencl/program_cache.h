#pragma once

#include <string>

#include "opencl/cl_api.h"

namespace mcquad {

//! The mcquad OpenCL program (embedded sources: shared headers + kernels)
//! built for one device, cached per (context, device, options, source hash)
//! for the life of the process. DeviceError with the build log and the
//! device name when the build fails.
cl::Program mcquad_program(const cl::Context& context, const cl::Device& device, const std::string& options = "");

//! The crossing guard's test of a step (kernels/guard.cl, double precision),
//! built and cached like mcquad_program; only for a device with
//! cl_khr_fp64 (has_double_precision).
cl::Program guard_program(const cl::Context& context, const cl::Device& device);
bool has_double_precision(const cl::Device& device);

//! The concatenated source the program is built from (for tests and tools).
std::string mcquad_program_source();

//! The shared headers alone, in the order the kernels need them: what any
//! program of mcquad's kernels starts with (the tests append their hooks).
std::string shared_kernel_source();

//! Builds `source` for one device, cached like mcquad_program.
cl::Program build_program(const cl::Context& context, const cl::Device& device, const std::string& source,
                          const std::string& options = "");

}  // namespace mcquad
