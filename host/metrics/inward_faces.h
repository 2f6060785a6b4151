#pragma once

#include <vector>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! Faces whose normal points against the scan's normal at the oriented
//! point nearest their centroid. The sample's order changes nothing but
//! which of two equally near points is taken; spatial order
//! (sort_spatially) builds its index 3x faster.
std::vector<int> faces_against_normals(const QuadMesh& mesh, const OrientedSample& oriented);

//! The share of the mesh's area that the given faces cover.
double area_fraction(const QuadMesh& mesh, const std::vector<int>& faces);

//! Faces whose normal points into the tube: toward the skeleton instead of
//! away (away from a smooth minimum of the distances to the bones, so a
//! crotch between bones counts its faces right). Approximate where the mesh
//! is far from its bones, e.g. around a junction the mesh builder moved.
size_t inward_faces(const QuadMesh& mesh, const SkeletonGraph& skeleton);
//! The same faces, by index.
std::vector<int> inward_face_indices(const QuadMesh& mesh, const SkeletonGraph& skeleton);

}  // namespace mcquad
