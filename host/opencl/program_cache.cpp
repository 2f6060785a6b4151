#include "opencl/program_cache.h"

#include <functional>
#include <map>
#include <mutex>
#include <tuple>

#include "core/errors.h"
#include "embedded_kernels.h"  // generated from kernels/ (cmake/embed_sources.cmake)

namespace mcquad {

std::string shared_kernel_source() {
  return std::string(embedded::mcq_platform_h) + embedded::mcq_philox_h + embedded::mcq_cell_tree_h +
         embedded::mcq_monte_carlo_h;
}

std::string mcquad_program_source() { return shared_kernel_source() + embedded::evolution_cl; }

cl::Program build_program(const cl::Context& context, const cl::Device& device, const std::string& source,
                          const std::string& options) {
  static std::mutex mutex;
  static std::map<std::tuple<cl_context, cl_device_id, std::string, size_t>, cl::Program> cache;
  const size_t source_hash = std::hash<std::string>()(source);
  std::lock_guard<std::mutex> lock(mutex);
  auto key = std::make_tuple(context(), device(), options, source_hash);
  auto found = cache.find(key);
  if (found != cache.end()) return found->second;
  cl::Program program(context, source);
  try {
    program.build({device}, options.c_str());
  } catch (const cl::Error&) {
    std::string log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
    throw DeviceError("OpenCL program build failed on " + device.getInfo<CL_DEVICE_NAME>() + ":\n" + log);
  }
  cache.emplace(key, program);
  return program;
}

std::string guard_program_source() {
  // Double precision, and no contraction of a * b + c into one rounding:
  // the host's guard rounds every operation, and the device must agree.
  return std::string("#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n#pragma OPENCL FP_CONTRACT OFF\n") +
         embedded::mcq_platform_h + embedded::mcq_guard_h + embedded::guard_cl;
}

bool has_double_precision(const cl::Device& device) {
  return device.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
}

cl::Program guard_program(const cl::Context& context, const cl::Device& device) {
  static const std::string kSource = guard_program_source();
  return build_program(context, device, kSource);
}

cl::Program mcquad_program(const cl::Context& context, const cl::Device& device, const std::string& options) {
  static const std::string kSource = mcquad_program_source();
  return build_program(context, device, kSource, options);
}

}  // namespace mcquad
