#include "mesh/folds.h"

namespace mcquad {

bool is_folded(const QuadMesh& mesh, QuadMesh::EdgeHandle edge) {
  if (mesh.is_boundary(edge)) return false;
  auto f0 = mesh.face_handle(mesh.halfedge_handle(edge, 0));
  auto f1 = mesh.face_handle(mesh.halfedge_handle(edge, 1));
  return normals_fold(face_vector_area(mesh, f0), face_vector_area(mesh, f1));
}

size_t folded_edges(const QuadMesh& mesh) {
  size_t folded = 0;
  for (auto e : mesh.edges()) folded += is_folded(mesh, e);
  return folded;
}

}  // namespace mcquad
