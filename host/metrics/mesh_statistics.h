#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/quad_mesh.h"

namespace mcquad {

//! Topology of a mesh.
struct MeshStatistics {
  size_t vertices = 0, faces = 0, quads = 0, edges = 0;
  size_t boundary_loops = 0;
  size_t components = 0;
  long euler_characteristic = 0;
  double quad_fraction = 0;
  size_t irregular_vertices = 0;  //!< valence != 4 inside, != 3 on a boundary
  size_t non_manifold_vertices = 0;
};

MeshStatistics mesh_statistics(const QuadMesh& mesh);

//! The centre (mean of the corners) of each boundary loop of the mesh.
std::vector<Eigen::Vector3d> boundary_loop_centres(const QuadMesh& mesh);

//! Indices of irregular vertices (valence != 4 inside, != 3 on a boundary).
std::vector<int> irregular_vertices(const QuadMesh& mesh);

nlohmann::json to_json(const MeshStatistics& statistics);

}  // namespace mcquad
