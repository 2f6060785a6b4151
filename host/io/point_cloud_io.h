#pragma once

#include <string>

#include "core/point_cloud.h"

namespace mcquad {

//! Reads a point cloud, format chosen by extension: .ply, .xyz/.txt/.csv
//! (whitespace- or comma-separated x y z, extra columns ignored, '#'
//! comments), .obj (v lines) and .off (vertices). InputError naming the file,
//! the line or element and the problem for anything malformed, non-finite or
//! empty. Normals are read only when asked for (the fit never needs them,
//! and they would double the memory of a large cloud): all of them with
//! `with_normals`, or with `sample_size` > 0 a strided sample of about
//! that many points with their normals, in cloud.oriented (what the verdict
//! judges orientation by).
PointCloud read_point_cloud(const std::string& path, bool with_normals = false, size_t sample_size = 0);

//! Writes a cloud by extension (.ply binary, .xyz text), atomically.
void write_point_cloud(const std::string& path, const PointCloud& cloud);

}  // namespace mcquad
