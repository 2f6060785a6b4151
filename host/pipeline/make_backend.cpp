#include "pipeline/make_backend.h"

#include "core/errors.h"
#include "core/progress.h"
#include "evolution/evolution_backend.h"
#include "evolution/serial_backend.h"
#ifdef MCQUAD_WITH_OPENCL
#include "opencl/opencl_backend.h"
#endif

namespace mcquad {

std::unique_ptr<EvolutionBackend> make_backend(BackendKind kind, const std::string& device) {
  if (kind == BackendKind::kSerial) return std::make_unique<SerialBackend>();
#ifdef MCQUAD_WITH_OPENCL
  try {
    return std::make_unique<OpenCLBackend>(select_device(device));
  } catch (const DeviceError& e) {
    // A device asked for by name or index is never silently replaced.
    if (kind == BackendKind::kOpenCL || !device.empty()) throw;
    warn(std::string("no usable OpenCL device, using the serial backend: ") + e.what());
    return std::make_unique<SerialBackend>();
  }
#else
  if (kind == BackendKind::kOpenCL || !device.empty())
    throw DeviceError("this build of mcquad has no OpenCL backend (MCQUAD_WITH_OPENCL=OFF)");
  return std::make_unique<SerialBackend>();
#endif
}

}  // namespace mcquad
