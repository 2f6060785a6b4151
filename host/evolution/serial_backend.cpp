#include "evolution/serial_backend.h"

namespace mcquad {

void SerialBackend::load(const CellTree& cells, const MeshArrays& mesh, const SkeletonRegions& regions) {
  cells_ = &cells;
  regions_ = &regions;
  mesh_ = mesh;
  positions_ = mesh.positions;
  next_positions_.resize(positions_.size());
  normals_.resize(positions_.size());
  update_normals();
  initial_normals_ = normals_;
  nearest_cells_.assign(mesh.vertex_count(), -1);
}

void SerialBackend::update_normals() {
  for (uint32_t v = 0; v < mesh_.vertex_count(); ++v)
    device::mcq_store3(normals_.data(), v,
                       device::mcq_vertex_normal(positions_.data(), mesh_.faces.data(),
                                                 mesh_.vertex_face_offsets.data(), mesh_.vertex_faces.data(), v));
}

void SerialBackend::relax(float weight) {
  for (uint32_t v = 0; v < mesh_.vertex_count(); ++v)
    device::mcq_store3(next_positions_.data(), v,
                       device::mcq_relaxed_position(positions_.data(), normals_.data(), mesh_.faces.data(),
                                                    mesh_.vertex_face_offsets.data(), mesh_.vertex_faces.data(),
                                                    mesh_.boundary.data(), v, weight));
  positions_.swap(next_positions_);
  update_normals();
}

void SerialBackend::step(const device::mcq_step_params& params) {
  if (params.relaxation > 0.0f) relax(params.relaxation);
  const device::mcq_topology topology = topology_view(mesh_);
  const device::mcq_cells cells = cells_view(*cells_);
  const device::mcq_regions regions = regions_view(*regions_);
  for (uint32_t v = 0; v < mesh_.vertex_count(); ++v) {
    uint32_t feasible;
    device::mcq_store3(
        next_positions_.data(), v,
        device::mcq_evolve_vertex(positions_.data(), normals_.data(), mesh_.positions.data(), initial_normals_.data(),
                                  topology, cells, regions, v, params, &feasible));
  }
  positions_.swap(next_positions_);
  update_normals();
}

void SerialBackend::set_positions(const std::vector<float>& positions) {
  positions_ = positions;
  update_normals();
}

double SerialBackend::error_level() { return mean_vertex_error(*cells_, positions_, &nearest_cells_); }

}  // namespace mcquad
