#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/quad_mesh.h"
#include "surfaces/patch_layout.h"

namespace mcquad {

//! A bicubic B-spline surface on uniform knots one apart, the paper's
//! "bicubic uniform B-spline". Per direction, with m data points along it:
//!  - clamped: knots 0, 1, ..., m-1, the end ones of multiplicity 4, and
//!    m + 2 poles; the surface spans the parameters [0, m-1];
//!  - periodic: knots 0, 1, ..., m, all simple, and m poles; pole k is the
//!    one centred at parameter k, S(k) = (P[k-1] + 4 P[k] + P[k+1]) / 6.
struct BSplineSurface {
  int poles_u = 0, poles_v = 0;
  bool periodic_u = false, periodic_v = false;
  std::vector<Eigen::Vector3d> poles;  //!< poles_u * poles_v, u fastest

  const Eigen::Vector3d& pole(int i, int j) const { return poles[size_t(j) * size_t(poles_u) + size_t(i)]; }
  //! Parameter range [0, span] in each direction.
  int spans_u() const { return periodic_u ? poles_u : poles_u - 3; }
  int spans_v() const { return periodic_v ? poles_v : poles_v - 3; }
};

//! The surface over one region that passes through every region vertex at
//! its grid parameter (i, j). Along a clamped side it takes, across the side,
//! the tangents grid_tangent gives (zero twist at the corners): two regions
//! that share a side compute the same curve and the same cross tangents
//! there, so they meet with matching tangent planes wherever the side's
//! vertices are regular, and only in position at irregular corners.
BSplineSurface interpolate_region(const QuadMesh& mesh, const PatchRegion& region);

}  // namespace mcquad
