#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "core/point_cloud.h"
#include "core/point_index.h"

namespace mcquad {

//! A capsule: the points within `radius` of segment [a, b]. An open end has
//! no cap: nothing is sampled past it, and for distances its wall goes on.
struct Capsule {
  Eigen::Vector3d a, b;
  double radius = 1;
  bool open_a = false, open_b = false;
};

//! The known surface of a generated shape: the boundary of a union of
//! capsules. Samples it uniformly by area and measures distances to it, so
//! tests can compare meshes with the true surface.
class TubeSurface {
 public:
  void add(const Capsule& capsule);
  const std::vector<Capsule>& capsules() const { return capsules_; }

  //! Signed distance to the union (negative inside). Exact outside; inside a
  //! junction, where capsules overlap, a lower bound of the true depth.
  double signed_distance(const Eigen::Vector3d& p) const;
  //! Which capsule is nearest (by signed distance), for local radii.
  int nearest_capsule(const Eigen::Vector3d& p) const;

  //! n points uniformly distributed by area over the union's boundary, with
  //! outward normals; each moved along its normal by N(0, noise * radius).
  PointCloud sample(size_t n, std::mt19937_64& random, double noise) const;

  nlohmann::json to_json() const;
  static TubeSurface from_json(const nlohmann::json& json);

 private:
  void build_index() const;
  double capsule_distance(size_t i, const Eigen::Vector3d& p) const;
  std::vector<size_t> candidates(const Eigen::Vector3d& p, double reach) const;

  std::vector<Capsule> capsules_;
  mutable std::vector<Eigen::Vector3d> midpoints_;
  mutable std::unique_ptr<PointIndex<double>> index_;
  mutable double max_half_length_ = 0, max_radius_ = 0;
};

}  // namespace mcquad
