#pragma once

#include <cstddef>

#include "core/quad_mesh.h"
#include "evolution/evolution_backend.h"
#include "evolution/evolution_parameters.h"
#include "mesh/mesh_arrays.h"
#include "mesh/scan_orientation.h"

namespace mcquad {

//! What the smoothing of turned faces did.
struct TurnedFaceSmoothing {
  size_t faces_before = 0, faces_after = 0;  //!< faces facing against the scan's normals
  double area_before = 0, area_after = 0;    //!< their share of the mesh's area
  int rounds = 0;                            //!< rounds taken, in both passes
  unsigned settle_iterations = 0;            //!< evolution steps between the passes
  //! Coarse to fine: the smoothed coarse fit crossed itself once refined,
  //! so the fit refined and evolved further is the one from before (pipeline/fit.cpp).
  bool undone_for_crossings = false;
  //! Deep vertices pushed out first (evolution/deep_vertex_push.h): the
  //! rounds that moved something, and whether the pushed fit was kept.
  int deep_push_rounds = 0;
  bool deep_push_kept = false;
};

//! Robust mode, after the evolution, on a scan with normals: where tubes meet
//! at a narrow crease, vertices from both walls settle on the surface but
//! the faces between them can end up turned against the scan. Each round
//! moves the corners of the faces that face inward
//! (mesh/scan_orientation.h) halfway to their neighbours' mean
//! (mesh/folds.h, relax_vertices), which lifts them out of the crease's
//! bottom and turns the faces back out; the crossing guard, started from
//! `start` (the positions the evolution started from, as the evolution's
//! own guard), shortens any move that would make faces cross, fold or turn
//! over. It stops when no face faces inward, after `rounds` rounds, or when
//! the guard holds every move back. Creases come out slightly rounded
//! (docs/DESIGN.md, "Turned faces in creases", has the measurements).
TurnedFaceSmoothing smooth_turned_faces(QuadMesh& mesh, const MeshArrays& start, const ScanOrientation& scan,
                                        int rounds);

//! Evolution steps after the first smoothing pass (turn_faces_out).
constexpr unsigned kSettleIterations = 3;

//! Robust mode's end of the evolution, on a scan with normals: `mesh` holds
//! the evolution's result on `backend` (loaded with `start`). Faces turned
//! against the scan are smoothed (parameters.turned_face_rounds rounds at
//! most); where that moved anything, the mesh settles back onto the cloud
//! for kSettleIterations more steps (numbered from `first_iteration`), since
//! the smoothing lifts parts of it off, and what those turned again is
//! smoothed once more. On the hand scan the smoothing alone halved the
//! turned area but let the cloud -> mesh 95th percentile grow by a third;
//! settling keeps the first and takes back the second (docs/DESIGN.md).
//! With parameters.push_deep (and an evolution of at least one iteration),
//! the same is done a second time on a copy whose
//! deep vertices were pushed out first (push_deep_vertices, kDeepVertexDepth
//! epsilon deep, then kSettleIterations steps): that copy is kept when the
//! area it turns against the scan (as the verdict counts it) is no larger.
TurnedFaceSmoothing turn_faces_out(EvolutionBackend& backend, const MeshArrays& start,
                                   const EvolutionParameters& parameters, const ScanOrientation& scan, QuadMesh& mesh,
                                   unsigned first_iteration);

}  // namespace mcquad
