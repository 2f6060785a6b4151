#pragma once

#include <cstdint>
#include <vector>

#include "mesh/mesh_arrays.h"

namespace mcquad {

//! Moves `vertices` toward the mean of their neighbours within their tangent
//! planes, by `weight` of the way (mcq_relaxed_position, the relaxation
//! robust mode offers before every step), reading `positions` and writing
//! the moved ones into `relaxed` (which the caller fills with `positions`,
//! so the other vertices stay). Tangential: it spreads vertices out without
//! pulling them off the surface, as the full umbrella step does.
void relax_tangentially(const MeshArrays& mesh, const std::vector<float>& positions,
                        const std::vector<uint32_t>& vertices, float weight, std::vector<float>& relaxed);

}  // namespace mcquad
