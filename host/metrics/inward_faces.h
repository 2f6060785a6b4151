#pragma once

#include <vector>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "mesh/scan_orientation.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! Faces whose normal points into the tube: toward the skeleton instead of
//! away (away from a smooth minimum of the distances to the bones, so a
//! crotch between bones counts its faces right). Approximate where the mesh
//! is far from its bones, e.g. around a junction the mesh builder moved.
size_t inward_faces(const QuadMesh& mesh, const SkeletonGraph& skeleton);
//! The same faces, by index.
std::vector<int> inward_face_indices(const QuadMesh& mesh, const SkeletonGraph& skeleton);

}  // namespace mcquad
