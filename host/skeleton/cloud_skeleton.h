#pragma once

#include <string>
#include <vector>

#include "core/point_cloud.h"
#include "io/skeleton_io.h"

namespace mcquad {

struct SkeletonExtractionOptions {
  //! Voxels the cloud is thinned to; 0 = a quarter of the points, at most
  //! 40,000 (the cost of every stage after binning, and the thinnest limb
  //! resolved: about a sixth of a voxel's ring count per radius).
  size_t target_voxels = 0;
  //! Width of a band of geodesic distance, in voxel edges.
  double band_voxels = 2.5;
};

//! A curve skeleton extracted from a cloud, with what it was made from.
struct ExtractedSkeleton {
  SkeletonData skeleton;
  std::vector<double> radii;  //!< per node: distance to the cloud (the inscribed ball)
  double voxel_size = 0;
  size_t voxels = 0;
  size_t discarded_voxels = 0;  //!< in pieces too small to be a body: outliers, specks
  int components = 0;
};

//! Extracts a curve skeleton from a cloud (no normals needed, any units):
//! the level-set (Reeb) graph of geodesic distance on a voxel graph of the
//! points, cleaned (spurs shorter than the local radius and cycles shorter
//! than a tube's girth removed), junction nodes moved to where their limbs'
//! axes meet, ends moved one radius in from a capped tip, and chains thinned
//! to the nodes their bends need. Deterministic. Errors name `source`:
//! InputError for too few points; UnsupportedError for a cloud with no curve
//! skeleton (a sheet, a blob with no limbs). See docs/SKELETON.md.
ExtractedSkeleton extract_skeleton(const PointCloud& cloud, const std::string& source,
                                   const SkeletonExtractionOptions& options = {});

}  // namespace mcquad
