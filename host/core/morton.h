#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace mcquad {

//! Spreads the low 21 bits of v to every third bit.
inline uint64_t spread_bits(uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}

//! The Morton (Z-order) code of a grid cell given by its non-negative
//! coordinates (truncated, at most 21 bits each): x in the lowest bit of
//! every triple, then y, then z. The point sort (sort_spatially) and the
//! sorted point tree use this one interleaving.
inline uint64_t morton_code(const Eigen::Vector3f& cell) {
  return spread_bits(uint64_t(cell.x())) | spread_bits(uint64_t(cell.y())) << 1 | spread_bits(uint64_t(cell.z())) << 2;
}

}  // namespace mcquad
