#include "evolution/tangential_relaxation.h"

#include "core/shared_math.h"

namespace mcquad {

void relax_tangentially(const MeshArrays& mesh, const std::vector<float>& positions,
                        const std::vector<uint32_t>& vertices, float weight, std::vector<float>& relaxed) {
  // The normals first, from the positions before any vertex moves.
  std::vector<float> normals(positions.size(), 0.0f);
  for (uint32_t v : vertices)
    device::mcq_store3(normals.data(), v,
                       device::mcq_vertex_normal(positions.data(), mesh.faces.data(), mesh.vertex_face_offsets.data(),
                                                 mesh.vertex_faces.data(), v));
  for (uint32_t v : vertices)
    device::mcq_store3(relaxed.data(), v,
                       device::mcq_relaxed_position(positions.data(), normals.data(), mesh.faces.data(),
                                                    mesh.vertex_face_offsets.data(), mesh.vertex_faces.data(),
                                                    mesh.boundary.data(), v, weight));
}

}  // namespace mcquad
