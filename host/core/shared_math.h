#pragma once

// The per-vertex math of kernels/shared/, compiled as C++ for the serial path
// (the OpenCL backend compiles the very same files as OpenCL C).
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>

namespace mcquad::device {
#include "mcq_platform.h"
#include "mcq_philox.h"
#include "mcq_cell_tree.h"
#include "mcq_monte_carlo.h"
#include "mcq_guard.h"
}  // namespace mcquad::device

namespace mcquad {

//! A host vector as the shared code's double vector (kernels/shared/mcq_guard.h).
inline device::mcq_d3 to_device(const Eigen::Vector3d& p) { return device::mcq_d3_make(p.x(), p.y(), p.z()); }

}  // namespace mcquad
