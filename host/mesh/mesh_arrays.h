#pragma once

#include <cstdint>
#include <vector>

#include "core/quad_mesh.h"
#include "core/shared_math.h"

namespace mcquad {

//! The mesh flattened for the evolution, structure of arrays, made once
//! after the topology is final: positions as floats, quads as 4 indices,
//! vertex->face adjacency in CSR form. OpenCL buffers mirror it one to one.
struct MeshArrays {
  std::vector<float> positions;               //!< 3 per vertex
  std::vector<uint32_t> faces;                //!< 4 per quad, counter-clockwise seen from outside
  std::vector<uint32_t> vertex_face_offsets;  //!< vertex v's faces: vertex_faces[offsets[v] .. offsets[v+1])
  std::vector<uint32_t> vertex_faces;
  std::vector<uint32_t> boundary;  //!< 1 for a vertex on an open boundary, else 0

  size_t vertex_count() const { return positions.size() / 3; }
  size_t face_count() const { return faces.size() / 4; }
};

//! The connectivity as the shared kernel code reads it (pointers into `mesh`).
inline device::mcq_topology topology_view(const MeshArrays& mesh) {
  return {mesh.faces.data(), mesh.vertex_face_offsets.data(), mesh.vertex_faces.data(), mesh.boundary.data()};
}

//! Flattens an all-quad mesh (UnsupportedError for any other face).
MeshArrays flatten_mesh(const QuadMesh& mesh);

//! The mesh's positions, flat, as floats (3 per vertex).
std::vector<float> mesh_positions(const QuadMesh& mesh);

//! Copies flat positions back into the mesh (same vertex order).
void set_positions(QuadMesh& mesh, const std::vector<float>& positions);

}  // namespace mcquad
