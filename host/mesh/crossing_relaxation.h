#pragma once

#include "core/quad_mesh.h"

namespace mcquad {

//! Where the tubes out of a junction block pass close by each other (many
//! bones in a plane, forks at 20-40 degrees), the rough mesh can have faces
//! that cross. Each round smooths (mesh/folds.h, relax_vertices) the vertices
//! of the crossing faces and the rings round them until none crosses; the
//! rings grow every ten rounds (one to six), for at most `rounds` rounds,
//! and it gives up after 20 rounds without fewer crossings than before.
//! Returns the crossing pairs left (0 unless it gave up).
size_t relax_crossings(QuadMesh& mesh, int rounds = 100);

}  // namespace mcquad
