#pragma once

#include <string>
#include <vector>

#include "core/point_cloud.h"
#include "generate/tube_surface.h"
#include "io/skeleton_io.h"

namespace mcquad {

struct ShapeOptions {
  size_t points = 0;  //!< 0 = the shape's default count
  double noise = 0;   //!< standard deviation along the normal, as a fraction of the tube radius
  uint64_t seed = 1;
  double angle_degrees = 0;    //!< y-fork: angle between the two branches (0 = 60); fan: between neighbours (0 = 30);
                               //!< thin-branch: between the branch and the trunk (0 = 60)
  double branch_radius = 0.2;  //!< thin-branch: the branch's radius, the trunk's being 1
  int arms = 4;                //!< star, planar-star: valence of the junction (3..16)
  // Scan defects (issue 6's cases):
  double outliers = 0;       //!< fraction of the points replaced by outliers at least a radius off the surface
  double density_ratio = 1;  //!< density falls linearly along x from 1 to 1/ratio (10 = tenfold)
  int holes = 0;             //!< patches of radius r left without points
  // Skeletons as other tools make them (issue 14's stand-ins); the surface
  // and the cloud stay as they are:
  double skeleton_offset = 0;  //!< every node moved off-centre by this fraction of its radius
  double short_ends = 0;       //!< every end node pulled back along its chain by this fraction of its radius
};

//! A synthetic cloud with its skeleton and its true surface.
struct GeneratedShape {
  std::string name;
  PointCloud cloud;
  SkeletonData skeleton;
  TubeSurface surface;
  int open_ends = 0;  //!< ends where the surface is open
  int independent_cycles = 0;
};

//! Names accepted by generate_shape, with one line describing each.
std::vector<std::pair<std::string, std::string>> shape_catalogue();

//! Makes a named shape: t-shape (Fig. 1, open leg), torus-knot (Fig. 7:
//! 413,696 points in the paper's box), tube-frame (Fig. 6 stand-in: 182,274
//! points in the paper's box), tube, bent-tube (open both ends), torus,
//! y-fork, star (one junction, valence 3..6, skew), theta (two junctions,
//! three chains), and for issue 6's hard cases: parallel-tubes (two tubes
//! half a radius apart), thin-branch (a branch a fifth of the trunk's radius),
//! tight-knot (a knot passing within a radius of itself). InputError for an
//! unknown name or a bad option.
GeneratedShape generate_shape(const std::string& name, const ShapeOptions& options);

//! Writes DIR/NAME.ply, DIR/NAME.skeleton.obj and DIR/NAME.surface.json.
void write_generated_shape(const GeneratedShape& shape, const std::string& directory);

}  // namespace mcquad
