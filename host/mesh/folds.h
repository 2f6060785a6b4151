#pragma once

#include <Eigen/Geometry>
#include <set>
#include <vector>

#include "core/quad_mesh.h"
#include "core/shared_math.h"

namespace mcquad {

//! The one fold test: two faces fold over each other when their normals
//! (any length) are more than 120 degrees apart, a face flipped over its
//! neighbour. The metrics count folds with it and the crossing guard holds
//! moves back with it.
inline bool normals_fold(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return device::mcq_guard_normals_fold(to_device(a), to_device(b)) != 0;  // kernels/shared/mcq_guard.h
}

//! Whether the two faces of an interior edge fold over each other.
bool is_folded(const QuadMesh& mesh, QuadMesh::EdgeHandle edge);

//! The edges whose faces fold over each other.
size_t folded_edges(const QuadMesh& mesh);

//! One round of umbrella smoothing: every interior vertex of `region` moves
//! halfway to its neighbours' mean (all from the positions before the round).
void relax_vertices(QuadMesh& mesh, const std::set<int>& region);

//! The corners of the given faces, as a region to relax.
std::set<int> corners_of(const QuadMesh& mesh, const std::vector<int>& faces);

//! Adds `rings` rings of edge neighbours round `region`.
void grow_region(const QuadMesh& mesh, std::set<int>& region, int rings);

//! Where tubes meet at a junction, refinement can leave a face folded over
//! its neighbour. Such places are relaxed (umbrella smoothing of the folded
//! faces' vertices and their neighbours) until no fold is left, for at most
//! 50 rounds. A fold that ten rounds do not undo takes one ring more with
//! it, up to `widening_rings` more: on a refined mesh that frees folds
//! wedged between neighbours, while on the unrefined one (8 vertices round a
//! tube) a wider ring would turn whole tubes over.
void relax_folds(QuadMesh& mesh, int widening_rings = 0);

}  // namespace mcquad
