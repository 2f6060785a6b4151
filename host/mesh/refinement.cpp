#include "mesh/refinement.h"

#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>

namespace mcquad {

void refine_catmull_clark(QuadMesh& mesh, int levels) {
  if (levels <= 0) return;
  OpenMesh::Subdivider::Uniform::CatmullClarkT<QuadMesh> subdivider;
  subdivider.attach(mesh);
  subdivider(size_t(levels));
  subdivider.detach();
}

}  // namespace mcquad
