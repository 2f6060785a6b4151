#pragma once

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "core/quad_mesh.h"

namespace mcquad {

//! How well shaped the quads are, which is what a B-spline fit of the mesh
//! cares about. Corner measures use the face's normal (its vector area), so
//! a corner folded against its face counts as inverted.
struct QuadShape {
  //! Scaled Jacobian of a quad: the smallest over its corners of
  //! (e1 x e2) . n / (|e1| |e2|), the sine of the corner angle, signed.
  //! 1: all corners square; 0: a degenerate corner; negative: inverted.
  double min_scaled_jacobian = 1, p5_scaled_jacobian = 1, mean_scaled_jacobian = 1;
  size_t faces_below_half = 0;  //!< scaled Jacobian under 0.5 (corners beyond 30..150 degrees)
  //! Longest over shortest edge of a quad.
  double max_edge_ratio = 1, p95_edge_ratio = 1;
  //! Corner angles over all quads, degrees.
  double min_angle = 90, max_angle = 90;
};

QuadShape measure_quad_shape(const QuadMesh& mesh);

//! The scaled Jacobian of one quad from its corners in order (as above).
double scaled_jacobian(const Eigen::Vector3d* corners);

nlohmann::json to_json(const QuadShape& shape);

}  // namespace mcquad
