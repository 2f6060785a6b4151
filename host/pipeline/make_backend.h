#pragma once

#include <memory>
#include <string>

#include "evolution/evolution_backend.h"

namespace mcquad {

//! Creates a backend; for kAuto, OpenCL when a device is usable (else serial,
//! saying so once on stderr). `device` selects an OpenCL device by index or
//! name ("" = MCQUAD_DEVICE or the first GPU, else the first device). It
//! sits above both backends, so that neither depends on the other.
std::unique_ptr<EvolutionBackend> make_backend(BackendKind kind, const std::string& device);

}  // namespace mcquad
