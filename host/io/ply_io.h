#pragma once

#include <string>

#include "core/point_cloud.h"

namespace mcquad {

//! Reads the vertex element of a PLY file (ascii, binary little or big
//! endian; coordinates of any scalar type; nx/ny/nz read when present, other
//! properties and elements skipped). Binary bodies are read in bulk. A header
//! whose counts the file cannot hold is an InputError, before any allocation.
//! With `oriented_sample` > 0 (and not `with_normals`), normals go to a
//! strided sample of about that many points (cloud.oriented), not one per point.
PointCloud read_ply_cloud(const std::string& path, bool with_normals = true, size_t oriented_sample = 0);

//! Writes a binary little-endian PLY with float x y z (and nx ny nz when the
//! cloud has normals), atomically.
void write_ply_cloud(const std::string& path, const PointCloud& cloud);

}  // namespace mcquad
