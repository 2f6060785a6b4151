#pragma once

#include <cstddef>

#include "core/quad_mesh.h"

namespace mcquad {

//! Where many bones leave one junction block (an octopus's mantle) or a
//! scan's skeleton bends hard at one, the rough mesh can keep quads with a
//! corner near 0 or 180 degrees, even inverted. The evolution's crossing
//! guard never lets a quad fall below where it started, but neither does it
//! raise one, so such a quad stays in the fitted mesh. Each round smooths
//! (mesh/folds.h, relax_vertices) the corners of the quads whose scaled
//! Jacobian is under `least`, with one ring round them, and relaxes any
//! fold that makes (relax_folds); a round that still leaves faces crossing
//! or folded that were not before is undone and tried on the corners alone,
//! and where that fails too, the relaxation stops. At most `rounds` rounds, and it gives up after ten without fewer
//! such quads. What smoothing leaves (a corner near 180 degrees beside a
//! junction's irregular vertex, where the neighbours' mean is no better) is
//! then straightened: each poor quad's corners move toward where they would
//! make it a parallelogram, as far as raises the least scaled Jacobian of
//! the quads round them without folding their edges, round by round (a
//! round that makes faces cross is undone). Returns how many are left.
size_t relax_poor_quads(QuadMesh& mesh, double least, int rounds = 50);

}  // namespace mcquad
