#pragma once

#include <string>

#include "core/quad_mesh.h"

namespace mcquad {

//! The extensions write_mesh accepts, for messages.
extern const char* const kMeshOutputExtensions;

//! Writes a mesh through OpenMesh's IO, format by extension (.obj, .off,
//! .ply, .om; .stl binary and .stla ASCII STL, with each quad split in two
//! triangles along its shorter diagonal), atomically. OutputError naming
//! the file on failure or for an unknown extension, listing the accepted ones.
void write_mesh(const std::string& path, const QuadMesh& mesh);

//! Reads a polygon mesh through OpenMesh's IO. InputError naming the file.
QuadMesh read_mesh(const std::string& path);

}  // namespace mcquad
