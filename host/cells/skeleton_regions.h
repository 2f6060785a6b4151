#pragma once

#include <cstdint>
#include <vector>

#include "cells/cell_tree.h"
#include "mesh/mesh_arrays.h"
#include "skeleton/acute_junctions.h"

namespace mcquad {

//! Robust mode's skeleton regions (docs/DESIGN.md): every cell and every
//! vertex belongs to its nearest bone, and a vertex sees only the cells of
//! the bones near its own along the skeleton, so its rays pass through
//! another tube, a branch's neighbour or the far side of a tight loop as if
//! it were not there. Also each vertex's local scale, by which robust mode
//! sizes its feasibility bound and ray reach, so a thin branch does not
//! look as far as the trunk. Layout as in kernels/shared/mcq_cell_tree.h:
//! bone b sees bones visible_bones[visible_offsets[b] .. visible_offsets[b+1]).
struct SkeletonRegions {
  std::vector<uint32_t> cell_bones;       //!< per cell: the bone nearest its centroid
  std::vector<uint32_t> vertex_bones;     //!< per vertex: the bone nearest its starting position
  std::vector<float> vertex_scale;        //!< per vertex: its bone's radius over the median radius
  std::vector<uint32_t> visible_offsets;  //!< per bone, CSR
  std::vector<uint32_t> visible_bones;    //!< sorted within each bone's run
};

//! The regions as the shared kernel code reads them (pointers into `regions`).
inline device::mcq_regions regions_view(const SkeletonRegions& regions) {
  return {regions.cell_bones.data(), regions.vertex_bones.data(), regions.vertex_scale.data(),
          regions.visible_offsets.data(), regions.visible_bones.data()};
}

//! Bone b sees the bones within `window` times its radius of it along the
//! skeleton (shortest path between their nearest ends; 0 for bones sharing
//! a node). Two radii cover the cloud a bone's tube owns around bends and
//! junctions; the other pass of a tight knot, a thin branch's trunk beyond
//! the junction and a separate tube are further.
SkeletonRegions build_skeleton_regions(const TubeSkeleton& skeleton, const CellTree& cells, const MeshArrays& mesh,
                                       double median_radius, double window = 2.0);

//! The longest cell the skeleton lets a tube have (build_cell_tree's
//! `longest_leaf`): half the radius of the bone nearest to the cell. Where
//! a randomly sampled cloud is sparse for its tube (the octopus's arms of
//! radius 0.32, 0.28 r between neighbours), a gap in it can leave a leaf of
//! two points a third of the way round the tube; a vertex in its box
//! averages their chord and stays inside (0.3 r on one arm, traced; the
//! octopus's mean / p95 distance to the true surface 1.44 / 5.11 -> 0.73 /
//! 2.57 % r). Densely sampled scans have few leaves that long: of the six
//! shared scans' figures one moved, by 0.0001 r (docs/HARD_CASES.md). The
//! function refers to `skeleton`, which must outlive it.
LongestLeaf longest_cell_by_radius(const TubeSkeleton& skeleton);

}  // namespace mcquad
