#pragma once

#include <Eigen/Geometry>
#include <cmath>

#include "core/point_cloud.h"
#include "core/point_index.h"
#include "core/quad_mesh.h"

namespace mcquad {

//! What the initial mesh asks of the cloud: its point spacing, how far the
//! cloud lies along a ray, and moving a smoothed mesh back inside it.
class CloudProbe {
 public:
  //! `cloud` and `index` (over its points) must outlive the probe.
  CloudProbe(const PointCloud& cloud, const PointIndex<float>& index)
      : cloud_(cloud), index_(index), spacing_(sample_spacing()) {}

  //! Typical distance between neighbouring cloud points (median over a
  //! deterministic subsample).
  double spacing() const { return spacing_; }

  //! Distance from `origin` along `direction` to the cloud: to the
  //! projection on the ray of the first nearest point found within three
  //! sample spacings of the ray (randomly sampled clouds have gaps of two
  //! spacings and more that a tighter bound lets rays slip through). Sphere
  //! tracing on the distance to the nearest point, stepping at least half a
  //! spacing where that point lies beside the ray rather than on it (a ray
  //! from a centre near a thin tube's wall still finds the wall across).
  //! Tracing stops once past `enough`: callers only need to know that much.
  double distance_along(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double enough) const;

  //! Distance from `p` to the nearest cloud point.
  double distance_to_cloud(const Eigen::Vector3d& p) const {
    return std::sqrt(double(index_.nearest(p.cast<float>()).second));
  }

  //! Catmull-Clark cuts corners: in a crease of the cloud (where tubes meet)
  //! a smoothed vertex can end up outside. Such vertices -- the cloud lies
  //! behind them along their normal, or nearer than two sample spacings --
  //! are moved back in along the normal. In a thin branch such a move can
  //! carry a vertex across the tube to the far wall, so the moves go through
  //! the evolution's crossing guard: none may make faces cross or fold.
  void keep_inside(QuadMesh& mesh) const;

 private:
  double sample_spacing() const;

  const PointCloud& cloud_;
  const PointIndex<float>& index_;
  double spacing_;
};

}  // namespace mcquad
