#pragma once

#include <string>
#include <vector>

#include "opencl/cl_api.h"

namespace mcquad {

struct DeviceInfo {
  int index = 0;  //!< position in the global list (platforms in order)
  std::string platform;
  std::string name;
  std::string type;  //!< "GPU", "CPU", "accelerator", "other"
  std::string version;
  unsigned compute_units = 0;
  unsigned long long global_memory = 0;
  cl::Device device;
};

//! Every OpenCL device of every platform; empty when there is no ICD or no
//! platform (never throws for that).
std::vector<DeviceInfo> list_devices();

//! Chooses a device: `request` (an index, or a substring of the name) if not
//! empty, else the MCQUAD_DEVICE environment variable, else the first GPU,
//! else the first device. DeviceError when none is usable or the request
//! matches none.
DeviceInfo select_device(const std::string& request);

}  // namespace mcquad
