#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "skeleton/cloud_skeleton.h"

namespace mcquad {

//! The report of an extraction: per node its position, radius and kind;
//! junctions, ends, cycles and components; the voxel graph it was made on.
nlohmann::json skeleton_report(const ExtractedSkeleton& extracted, const std::string& points_name, double seconds);

//! extract_skeleton, its time (seconds) given too: for the report.
ExtractedSkeleton extract_skeleton_timed(const PointCloud& cloud, const std::string& name,
                                         const SkeletonExtractionOptions& options, double& seconds);

//! `mcquad skeleton`: reads the cloud (no normals needed) and extracts its
//! skeleton; `seconds` gets the extraction's time (the reading excluded).
ExtractedSkeleton extract_skeleton_from_file(const std::string& points_path, const SkeletonExtractionOptions& options,
                                             double& seconds);

}  // namespace mcquad
