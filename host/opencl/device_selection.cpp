#include "opencl/device_selection.h"

#include <cstdlib>

#include "core/errors.h"
#include "io/file_utils.h"

namespace mcquad {
namespace {

std::string type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

//! "2 found: 0 'name', 1 'name'": what a wrong request could have asked for.
std::string found_devices(const std::vector<DeviceInfo>& devices) {
  std::string text = std::to_string(devices.size()) + " found:";
  for (const auto& d : devices) text += (d.index > 0 ? ", " : " ") + std::to_string(d.index) + " '" + d.name + "'";
  return text;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> devices;
  std::vector<cl::Platform> platforms;
  try {
    cl::Platform::get(&platforms);
  } catch (const cl::Error&) {
    return devices;  // no ICD loader or no platform: simply no devices
  }
  for (const auto& platform : platforms) {
    std::vector<cl::Device> platform_devices;
    try {
      platform.getDevices(CL_DEVICE_TYPE_ALL, &platform_devices);
    } catch (const cl::Error&) {
      continue;
    }
    for (const auto& device : platform_devices) {
      DeviceInfo info;
      info.index = int(devices.size());
      info.platform = platform.getInfo<CL_PLATFORM_NAME>();
      info.name = device.getInfo<CL_DEVICE_NAME>();
      info.type = type_name(device.getInfo<CL_DEVICE_TYPE>());
      info.version = device.getInfo<CL_DEVICE_VERSION>();
      info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.global_memory = device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.device = device;
      devices.push_back(info);
    }
  }
  return devices;
}

DeviceInfo select_device(const std::string& request) {
  std::vector<DeviceInfo> devices = list_devices();
  if (devices.empty()) throw DeviceError("no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
  std::string wanted = request;
  const char* env = std::getenv("MCQUAD_DEVICE");
  if (wanted.empty() && env) wanted = env;
  if (!wanted.empty()) {
    long long index;
    if (parse_integer(wanted, index)) {
      if (index < 0 || index >= static_cast<long long>(devices.size()))
        throw DeviceError("OpenCL device " + wanted + " does not exist (" + found_devices(devices) + ")");
      return devices[size_t(index)];
    }
    for (const auto& d : devices)
      if (d.name.find(wanted) != std::string::npos || d.platform.find(wanted) != std::string::npos) return d;
    throw DeviceError("no OpenCL device matches '" + wanted + "' (" + found_devices(devices) + ")");
  }
  for (const auto& d : devices)
    if (d.type == "GPU") return d;
  return devices.front();
}

}  // namespace mcquad
