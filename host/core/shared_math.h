#pragma once

// The per-vertex math of kernels/shared/, compiled as C++ for the serial path
// (the OpenCL backend compiles the very same files as OpenCL C).
#include <cmath>
#include <cstdint>
#include <limits>

namespace mcquad::device {
#include "mcq_platform.h"
#include "mcq_philox.h"
#include "mcq_cell_tree.h"
#include "mcq_monte_carlo.h"
}  // namespace mcquad::device
