#pragma once

// numpy arrays to and from the library's types. Every conversion checks the
// array's shape and values and throws InputError naming `name`, as the
// file readers do for files.
#include <pybind11/numpy.h>

#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "io/skeleton_io.h"

namespace mcquad {

// forcecast: float64 points become float32 (what the pipeline and the
// readers use); any integer type becomes int64.
using FloatArray = pybind11::array_t<float, pybind11::array::c_style | pybind11::array::forcecast>;
using DoubleArray = pybind11::array_t<double, pybind11::array::c_style | pybind11::array::forcecast>;
using IndexArray = pybind11::array_t<int64_t, pybind11::array::c_style | pybind11::array::forcecast>;

//! A cloud from an (N, 3) array, with an optional (N, 3) array of normals
//! (None: none).
PointCloud cloud_from_array(const FloatArray& points, const std::string& name,
                            const pybind11::object& normals = pybind11::none());
//! Nodes (M, 3) and bones (E, 2) of 0-based node indices.
SkeletonData skeleton_from_arrays(const DoubleArray& nodes, const IndexArray& edges, const std::string& name);
//! Vertices (V, 3) and faces (F, k) of 0-based vertex indices; -1 pads faces of fewer than k corners.
QuadMesh mesh_from_arrays(const DoubleArray& vertices, const IndexArray& faces, const std::string& name);

FloatArray points_of(const PointCloud& cloud);
DoubleArray nodes_of(const SkeletonData& skeleton);
IndexArray edges_of(const SkeletonData& skeleton);
DoubleArray vertices_of(const QuadMesh& mesh);
//! (F, k) with k the largest face's corner count, -1 padding smaller faces.
IndexArray faces_of(const QuadMesh& mesh);

}  // namespace mcquad
