#pragma once

#include <string>

#include "core/point_cloud.h"

namespace mcquad {

//! Reads a point cloud, format chosen by extension: .ply, .xyz/.txt/.csv
//! (whitespace- or comma-separated x y z, extra columns ignored, '#'
//! comments), .obj (v lines) and .off (vertices). InputError naming the file,
//! the line or element and the problem for anything malformed, non-finite or
//! empty. Normals are read only when asked for (mcquad never needs them,
//! and they would double the memory of a large cloud).
PointCloud read_point_cloud(const std::string& path, bool with_normals = false);

//! Writes a cloud by extension (.ply binary, .xyz text), atomically.
void write_point_cloud(const std::string& path, const PointCloud& cloud);

}  // namespace mcquad
