#pragma once

// The Khronos C++ bindings (Debian's opencl-clhpp-headers), OpenCL 1.2, with
// exceptions: every failing call throws cl::Error carrying the call's name,
// which the backend turns into a DeviceError naming the device.
#define CL_HPP_ENABLE_EXCEPTIONS
#define CL_HPP_TARGET_OPENCL_VERSION 120
#define CL_HPP_MINIMUM_OPENCL_VERSION 120
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wignored-attributes"
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#include <CL/opencl.hpp>
#pragma GCC diagnostic pop

#include <string>

namespace mcquad {

//! Human-readable name of an OpenCL error code.
std::string cl_error_name(cl_int code);

}  // namespace mcquad
