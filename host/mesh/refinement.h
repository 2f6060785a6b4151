#pragma once

#include "core/quad_mesh.h"

namespace mcquad {

//! Catmull-Clark subdivision (OpenMesh's), `levels` times: every quad split in
//! four and smoothed. Existing vertices keep their indices; new ones follow.
void refine_catmull_clark(QuadMesh& mesh, int levels);

}  // namespace mcquad
