#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "io/skeleton_io.h"
#include "metrics/verdict.h"

namespace mcquad {

struct MeshMeasurement {
  nlohmann::json metrics;  //!< the report's "metrics" section, with "verdict" added
  Verdict verdict;
};

//! `mcquad metrics` and the Python package's metrics(): a mesh measured
//! against its cloud with the cells built as fit builds them (`leaf_size` 0:
//! automatic), and judged as fit judges it. Inward faces are told by the
//! cloud's normals when it has them, else by the skeleton. With a skeleton,
//! the default construction on it gives the radius that scales the
//! distance checks and the open ends the mesh must have; without one those
//! checks are left out (nothing says what is near). Pass the cloud in
//! spatial order (sort_spatially), as fit has it: the figures are then fit's
//! to the last digit, and the cloud -> mesh search, which starts from the
//! previous point's triangle, takes a fraction of the time.
MeshMeasurement measure_mesh(const QuadMesh& mesh, const PointCloud& cloud, const SkeletonData* skeleton,
                             const std::string& skeleton_name, size_t leaf_size);

}  // namespace mcquad
