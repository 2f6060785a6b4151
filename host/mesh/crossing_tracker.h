#pragma once

#include <utility>
#include <vector>

#include "core/quad_mesh.h"
#include "mesh/close_triangle_pairs.h"

namespace mcquad {

//! The crossing face pairs of a mesh whose vertices move a few at a time
//! (the smoothing rounds of the construction's untangling and quad
//! relaxation): the first search covers the whole mesh; later ones look
//! again only at the faces round the vertices that moved since, through a
//! Verlet list (mesh/close_triangle_pairs.h). Every answer is
//! intersecting_face_pairs(mesh)'s, pair for pair. Refining the armadillo's
//! coarse fit to 92,674 vertices, untangling included, went 7.6 -> 3.1 s
//! with it and the guard's list (docs/PERFORMANCE.md).
class CrossingTracker {
 public:
  //! Searches `mesh` whole; its faces must stay the same from call to call.
  explicit CrossingTracker(const QuadMesh& mesh);

  //! The crossing face pairs (a < b, sorted) at the mesh's positions now.
  std::vector<std::pair<int, int>> pairs(const QuadMesh& mesh);

 private:
  MeshTriangles triangles_;  //!< the mesh's triangles at the positions last searched
  CloseTrianglePairs close_;
  std::vector<std::pair<int, int>> pairs_;  //!< the answer at triangles_' positions
};

}  // namespace mcquad
