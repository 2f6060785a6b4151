#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "skeleton/cloud_skeleton.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! The report of an extraction: per node its position, radius, kind and
//! degree; junctions, ends, cycles and components; the voxel graph it was
//! made on.
struct SkeletonReport {
  std::string points;
  std::vector<Eigen::Vector3d> positions;
  std::vector<double> radii;
  std::vector<NodeKind> kinds;
  std::vector<int> degrees;
  size_t bones = 0;
  int junctions = 0, ends = 0, independent_cycles = 0, components = 0;
  double voxel_size = 0;
  size_t voxels = 0, discarded_voxels = 0;
  double seconds = 0;  //!< the extraction's (the reading excluded)
  //! A limb the fit left out because its tube overlapped another's in the
  //! initial mesh (pipeline/fit.cpp): its end node, and where the overlap was.
  struct DroppedLimb {
    Eigen::Vector3d end, overlap;
  };
  std::vector<DroppedLimb> dropped_limbs;
};

SkeletonReport skeleton_report(const ExtractedSkeleton& extracted, const std::string& points_name, double seconds);

//! The report as `mcquad skeleton --report` writes it (and fit's "skeleton_extraction").
nlohmann::json to_json(const SkeletonReport& report);

//! extract_skeleton, its time (seconds) given too: for the report.
ExtractedSkeleton extract_skeleton_timed(const PointCloud& cloud, const std::string& name,
                                         const SkeletonExtractionOptions& options, double& seconds);

//! `mcquad skeleton`: reads the cloud (no normals needed) and extracts its
//! skeleton; `seconds` gets the extraction's time (the reading excluded).
ExtractedSkeleton extract_skeleton_from_file(const std::string& points_path, const SkeletonExtractionOptions& options,
                                             double& seconds);

}  // namespace mcquad
