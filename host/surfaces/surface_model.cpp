#include "surfaces/surface_model.h"

namespace mcquad {

SurfaceModel build_surface_model(const QuadMesh& mesh) {
  SurfaceModel model;
  model.layout = decompose_into_patches(mesh);
  model.surfaces.reserve(model.layout.regions.size());
  for (const PatchRegion& region : model.layout.regions) model.surfaces.push_back(interpolate_region(mesh, region));
  return model;
}

QuadMesh control_net_mesh(const std::vector<BSplineSurface>& surfaces) {
  QuadMesh net;
  for (const BSplineSurface& s : surfaces) {
    std::vector<QuadMesh::VertexHandle> handles;
    handles.reserve(s.poles.size());
    for (const Eigen::Vector3d& p : s.poles) handles.push_back(net.add_vertex(QuadMesh::Point(p.x(), p.y(), p.z())));
    int cells_u = s.periodic_u ? s.poles_u : s.poles_u - 1;
    int cells_v = s.periodic_v ? s.poles_v : s.poles_v - 1;
    auto at = [&](int i, int j) { return handles[size_t(j % s.poles_v) * size_t(s.poles_u) + size_t(i % s.poles_u)]; };
    for (int j = 0; j < cells_v; ++j)
      for (int i = 0; i < cells_u; ++i) net.add_face(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
  }
  return net;
}

}  // namespace mcquad
