#pragma once

#include <string>

#include "core/quad_mesh.h"

namespace mcquad {

//! Writes a mesh through OpenMesh's IO, format by extension (.obj, .off,
//! .ply, .om), atomically. OutputError naming the file on failure or for an
//! unknown extension.
void write_mesh(const std::string& path, const QuadMesh& mesh);

//! Reads a polygon mesh through OpenMesh's IO. InputError naming the file.
QuadMesh read_mesh(const std::string& path);

}  // namespace mcquad
