#pragma once

#include "core/quad_mesh.h"
#include "mesh/mesh_arrays.h"
#include "mesh/scan_orientation.h"

namespace mcquad {

//! How deep below the scan, in epsilon, a vertex must lie to be pushed out.
constexpr double kDeepVertexDepth = 0.25;

//! Robust mode, after the evolution, on a scan with normals: vertices the
//! evolution left deeper than `depth` below the scan (along the normal of
//! the nearest oriented point: a region the rays never reached, a hole in the
//! scan, a slot the mesh left in a crease) move out along that normal by half
//! their depth, each round. The moves are first averaged over each vertex's
//! one-ring (a vertex not pushed counts as a move of zero), so that
//! neighbours on the two walls of a crease, whose nearest normals differ,
//! move together and the pushes fade toward a pushed region's fringe (the
//! vertices not pushed stay, and a lone deep vertex's push, averaged four
//! times with four unpushed neighbours, all but vanishes); the
//! crossing guard, started from `start`, shortens any move that would make
//! faces cross, fold or turn over. At most `rounds` rounds; fewer once no
//! vertex is that deep or the guard holds every move back. Returns the
//! rounds that moved something.
int push_deep_vertices(QuadMesh& mesh, const MeshArrays& start, const ScanOrientation& scan, double depth, int rounds);

}  // namespace mcquad
