#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/quad_mesh.h"

namespace mcquad {

//! One regular region of a quad mesh: a rectangular grid of quads, the
//! control net of one bicubic B-spline surface. Vertex (i, j) sits at
//! parameter (u, v) = (i, j). A periodic direction has as many vertex
//! columns (rows) as faces around; a clamped one has one more. A region that
//! closes on itself with a shift (a torus whose rings come back rotated) is
//! clamped in u, and its last column repeats the first one shifted: the seam
//! between them is an ordinary seam between two sides.
struct PatchRegion {
  int columns = 0, rows = 0;  //!< vertex counts along u and v
  bool periodic_u = false, periodic_v = false;
  std::vector<int> vertices;  //!< columns * rows vertex ids, u fastest (ids repeat on a shifted seam)
  std::vector<int> faces;     //!< mesh faces of the region

  int vertex(int i, int j) const { return vertices[size_t(j) * size_t(columns) + size_t(i)]; }
};

//! The mesh cut into regular regions along separatrices: the edge lines that
//! start at every irregular vertex (interior valence other than 4, boundary
//! valence other than 3) and run straight through regular vertices until
//! they reach another irregular vertex, the boundary or themselves. Every
//! region left between them is a rectangle, a cylinder or a torus of quads.
struct PatchLayout {
  std::vector<PatchRegion> regions;
  //! Per face: its region, and the (u, v) parameters of its four corners in
  //! that region's surface (in face order; periodic regions may run past the
  //! period, so a face's corners are always a unit square).
  std::vector<int> face_region;
  std::vector<std::array<Eigen::Vector2d, 4>> face_corner_parameters;
  size_t irregular_vertices = 0;
  size_t separatrix_edges = 0;
  //! Faces of regions that did not come out rectangular (a mesh that is not
  //! a clean quad layout); each became a one-face region of its own.
  size_t single_face_fallbacks = 0;
};

//! Decomposes an all-quad, 2-manifold, consistently oriented mesh.
//! Throws UnsupportedError for faces that are not quads.
PatchLayout decompose_into_patches(const QuadMesh& mesh);

//! Derivative, per unit of the grid parameter, of a surface through the mesh
//! vertices at vertex p in the direction of its neighbour q. At an interior
//! vertex, the first Fourier harmonic of p's edge ring (the central
//! difference at valence 4; in p's tangent plane at other valences); along a
//! smooth open rim, the central difference along the rim; elsewhere on the
//! boundary the edge laid into p's tangent plane. It depends on the mesh
//! only, so regions that share p use the same vectors: their surfaces meet
//! with one tangent plane at every seam vertex.
Eigen::Vector3d grid_tangent(const QuadMesh& mesh, QuadMesh::VertexHandle p, QuadMesh::VertexHandle q);

}  // namespace mcquad
