#include "mesh/cloud_probe.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/shared_math.h"
#include "mesh/crossing_guard.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {

double CloudProbe::distance_along(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                  double enough) const {
  const double near = 3.0 * spacing_, least_step = std::max(0.5 * spacing_, 1e-3 * enough);
  double t = 0;
  for (int step = 0; step < 512 && t < enough; ++step) {
    Eigen::Vector3d p = origin + t * direction;
    auto [nearest, d2] = index_.nearest(p.cast<float>());
    double gap = std::sqrt(double(d2));
    Eigen::Vector3d w = cloud_.points[size_t(nearest)].cast<double>() - origin;
    double along = w.dot(direction);
    if ((w - along * direction).norm() < near && along >= 0) return along;
    t += std::max(gap - near, least_step);
  }
  return t;
}

double CloudProbe::sample_spacing() const {
  std::vector<double> gaps;
  size_t stride = std::max<size_t>(1, cloud_.size() / 500);
  for (size_t i = 0; i < cloud_.size(); i += stride) {
    auto neighbours = index_.k_nearest(cloud_.points[i], 2);
    if (neighbours.size() == 2) gaps.push_back((cloud_.points[neighbours[1]] - cloud_.points[i]).norm());
  }
  if (gaps.empty()) return 0.0;
  std::nth_element(gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
  return gaps[gaps.size() / 2];
}

void CloudProbe::keep_inside(QuadMesh& mesh) const {
  MeshArrays arrays = flatten_mesh(mesh);
  std::vector<float> moved = arrays.positions;
  double margin = 2.0 * spacing_;
  // Each vertex reads the mesh and the cloud and writes its own place: on all cores.
  const long vertices = long(mesh.n_vertices());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < vertices; ++i) {
    const auto v = mesh.vertex_handle(int(i));
    device::mcq_vec3 nv =
        device::mcq_vertex_normal(arrays.positions.data(), arrays.faces.data(), arrays.vertex_face_offsets.data(),
                                  arrays.vertex_faces.data(), uint32_t(v.idx()));
    Eigen::Vector3d n(nv.x, nv.y, nv.z);
    const auto& q = mesh.point(v);
    Eigen::Vector3d p(q[0], q[1], q[2]);
    Eigen::Vector3d w = cloud_.points[index_.nearest(p.cast<float>()).first].cast<double>() - p;
    double ahead = w.dot(n);
    // Capped: in a thin part the nearest point can lie behind a vertex
    // that is inside (on the far wall); a long shift would cross it.
    double shift = ahead < margin ? std::min(margin - ahead, 2.0 * margin) : 0.0;
    for (int k = 0; k < 3; ++k) moved[3 * size_t(v.idx()) + size_t(k)] = float(p[k] - shift * n[k]);
  }
  CrossingGuard(arrays).apply(arrays.positions, moved);
  for (auto v : mesh.vertices()) {
    const float* m = &moved[3 * size_t(v.idx())];
    const float* before = &arrays.positions[3 * size_t(v.idx())];
    if (m[0] != before[0] || m[1] != before[1] || m[2] != before[2])
      mesh.set_point(v, QuadMesh::Point(m[0], m[1], m[2]));
  }
}

}  // namespace mcquad
