#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "io/skeleton_io.h"

namespace mcquad {

//! `mcquad metrics` and the Python package's metrics(): a mesh measured
//! against its cloud (and skeleton, when given, for the faces turned into
//! the tube), with the cells built as fit builds them (`leaf_size` 0:
//! automatic). Returns the report's "metrics" section.
nlohmann::json measure_mesh(const QuadMesh& mesh, const PointCloud& cloud, const SkeletonData* skeleton,
                            const std::string& skeleton_name, size_t leaf_size);

}  // namespace mcquad
