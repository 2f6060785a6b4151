#pragma once

#include "core/quad_mesh.h"
#include "mesh/cloud_probe.h"
#include "skeleton/acute_junctions.h"

namespace mcquad {

//! Moves the initial mesh round each junction outward along rays from the
//! junction's node, to `fraction` of the way to the cloud along each ray,
//! within 2.5 of the junction's largest bone radius (fading out over the
//! outer half). Where tubes meet, their union is star-shaped about the node
//! (each tube contains it), so a move along the node's rays keeps the mesh
//! embedded where moves along vertex normals would compress the concave
//! creases between the tubes and be held back by the crossing guard, deep
//! inside (docs/DESIGN.md, "Junctions inflated from their node"). A ray that
//! runs on through a gap in the cloud (a hole beside the node) is not
//! followed: a vertex whose ray meets the cloud more than three times its
//! distance to the cloud away gets no offset of its own (smoothing may still
//! hand it part of its neighbours'). Offsets are smoothed over neighbours;
//! a move is halved until the vertex stays two sample spacings inside the
//! cloud; no vertex moves nearer to the skeleton. The moves go through the
//! crossing guard: none makes faces cross or fold.
void inflate_junctions(QuadMesh& mesh, const TubeSkeleton& skeleton, const CloudProbe& probe, double fraction);

}  // namespace mcquad
