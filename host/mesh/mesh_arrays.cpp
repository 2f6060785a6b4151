#include "mesh/mesh_arrays.h"

#include "core/errors.h"

namespace mcquad {

MeshArrays flatten_mesh(const QuadMesh& mesh) {
  MeshArrays arrays;
  arrays.positions = mesh_positions(mesh);
  for (auto v : mesh.vertices()) arrays.boundary.push_back(mesh.is_boundary(v) ? 1u : 0u);
  std::vector<uint32_t> counts(mesh.n_vertices() + 1, 0);
  for (auto f : mesh.faces()) {
    if (mesh.valence(f) != 4)
      throw UnsupportedError("the mesh has a face with " + std::to_string(mesh.valence(f)) +
                             " sides; only quads are supported");
    for (auto v : mesh.fv_range(f)) {
      arrays.faces.push_back(uint32_t(v.idx()));
      ++counts[v.idx() + 1];
    }
  }
  arrays.vertex_face_offsets.resize(mesh.n_vertices() + 1, 0);
  for (size_t v = 0; v < mesh.n_vertices(); ++v)
    arrays.vertex_face_offsets[v + 1] = arrays.vertex_face_offsets[v] + counts[v + 1];
  arrays.vertex_faces.resize(arrays.faces.size());
  std::vector<uint32_t> cursor(arrays.vertex_face_offsets.begin(), arrays.vertex_face_offsets.end() - 1);
  for (size_t f = 0; f < arrays.face_count(); ++f)
    for (int k = 0; k < 4; ++k) arrays.vertex_faces[cursor[arrays.faces[4 * f + k]]++] = uint32_t(f);
  return arrays;
}

std::vector<float> mesh_positions(const QuadMesh& mesh) {
  std::vector<float> positions;
  positions.reserve(3 * mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    positions.insert(positions.end(), {float(p[0]), float(p[1]), float(p[2])});
  }
  return positions;
}

void set_positions(QuadMesh& mesh, const std::vector<float>& positions) {
  for (auto v : mesh.vertices()) {
    size_t i = 3 * size_t(v.idx());
    mesh.set_point(v, QuadMesh::Point(positions[i], positions[i + 1], positions[i + 2]));
  }
}

}  // namespace mcquad
