#pragma once

#include <Eigen/Geometry>

#include "core/quad_mesh.h"

namespace mcquad {

//! Generalized winding number of the mesh at p (quads split in two
//! triangles): about 1 inside a closed, outward-oriented mesh, 0 outside,
//! -1 inside one oriented inward.
double winding_number(const QuadMesh& mesh, const Eigen::Vector3d& p);

}  // namespace mcquad
