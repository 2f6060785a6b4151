#include "generate/tube_surface.h"

#include <cmath>

#include "core/errors.h"
#include "core/progress.h"

namespace mcquad {
namespace {

//! How far an open end's wall is extended, in radii, for distance queries
//! (a mesh reaching past the rim is measured against the tube's cylinder,
//! not its round cap) and for sampling (the previous capsule's round end,
//! reaching out of a last capsule shorter than the radius, stays
//! unsampled). Fits reach at most 0.08 radii past their rims (37 shapes
//! of scripts/junction-bounds, docs/HARD_CASES.md); at 3 radii random tree
//! 14's open end reached into the wall of a tube passing beside it: that
//! wall was left unsampled, and measured as lying inside the shape.
constexpr double kOpenExtension = 1.0;

Eigen::Vector3d perpendicular(const Eigen::Vector3d& n) { return n.unitOrthogonal(); }

}  // namespace

void TubeSurface::add(const Capsule& capsule) {
  capsules_.push_back(capsule);
  index_.reset();
}

void TubeSurface::build_index() const {
  if (index_) return;
  midpoints_.clear();
  max_half_length_ = max_radius_ = 0;
  for (const auto& c : capsules_) {
    midpoints_.emplace_back(0.5 * (c.a + c.b));
    double extra = (c.open_a || c.open_b) ? kOpenExtension * c.radius : 0.0;
    max_half_length_ = std::max(max_half_length_, 0.5 * (c.b - c.a).norm() + extra);
    max_radius_ = std::max(max_radius_, c.radius);
  }
  index_ = std::make_unique<PointIndex<double>>(midpoints_);
}

double TubeSurface::capsule_distance(size_t i, const Eigen::Vector3d& p) const {
  const Capsule& c = capsules_[i];
  Eigen::Vector3d direction = (c.b - c.a).normalized();
  Eigen::Vector3d a = c.open_a ? Eigen::Vector3d(c.a - kOpenExtension * c.radius * direction) : c.a;
  Eigen::Vector3d b = c.open_b ? Eigen::Vector3d(c.b + kOpenExtension * c.radius * direction) : c.b;
  Eigen::Vector3d ab = b - a;
  double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm() - c.radius;
}

std::vector<size_t> TubeSurface::candidates(const Eigen::Vector3d& p, double reach) const {
  build_index();
  return index_->within(p, reach + max_half_length_ + max_radius_);
}

int TubeSurface::nearest_capsule(const Eigen::Vector3d& p) const {
  build_index();
  // The nearest midpoints bound the distance; then every capsule that could
  // beat that bound is checked.
  double bound = INFINITY;
  for (size_t i : index_->k_nearest(p, 8)) bound = std::min(bound, capsule_distance(i, p));
  int best = -1;
  double best_distance = INFINITY;
  for (size_t i : candidates(p, std::abs(bound) + max_radius_)) {
    double d = capsule_distance(i, p);
    if (d < best_distance) {
      best_distance = d;
      best = int(i);
    }
  }
  return best;
}

double TubeSurface::signed_distance(const Eigen::Vector3d& p) const {
  int i = nearest_capsule(p);
  return i < 0 ? INFINITY : capsule_distance(size_t(i), p);
}

PointCloud TubeSurface::sample(size_t n, std::mt19937_64& random, double noise) const {
  if (capsules_.empty()) throw InputError("cannot sample an empty surface");
  build_index();
  std::vector<double> cumulative;
  double total = 0;
  for (const auto& c : capsules_) {
    double caps = (c.open_a ? 0 : 2) + (c.open_b ? 0 : 2);
    total += 2 * M_PI * c.radius * (c.b - c.a).norm() + caps * M_PI * c.radius * c.radius;
    cumulative.push_back(total);
  }
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PointCloud cloud;
  cloud.points.reserve(n);
  cloud.normals.reserve(n);
  Progress progress("sampling", n);
  while (cloud.size() < n) {
    size_t i =
        size_t(std::lower_bound(cumulative.begin(), cumulative.end(), uniform(random) * total) - cumulative.begin());
    i = std::min(i, capsules_.size() - 1);
    const Capsule& c = capsules_[i];
    double length = (c.b - c.a).norm();
    Eigen::Vector3d axis = (c.b - c.a) / length;
    double cylinder = 2 * M_PI * c.radius * length;
    double caps = ((c.open_a ? 0 : 2) + (c.open_b ? 0 : 2)) * M_PI * c.radius * c.radius;
    Eigen::Vector3d point, normal;
    if (uniform(random) * (cylinder + caps) < cylinder) {
      Eigen::Vector3d u = perpendicular(axis), v = axis.cross(u);
      double angle = 2 * M_PI * uniform(random);
      normal = std::cos(angle) * u + std::sin(angle) * v;
      point = c.a + uniform(random) * length * axis + c.radius * normal;
    } else {
      normal = Eigen::Vector3d(gauss(random), gauss(random), gauss(random)).normalized();
      bool at_b = normal.dot(axis) > 0;
      if ((at_b && c.open_b) || (!at_b && c.open_a)) normal = normal - 2 * normal.dot(axis) * axis;
      at_b = normal.dot(axis) > 0;
      point = (at_b ? c.b : c.a) + c.radius * normal;
    }
    // Keep the point only where it is on the union's boundary: outside every
    // other capsule, and on shared boundaries only for the lowest index.
    bool keep = true;
    for (size_t j : candidates(point, 0.0)) {
      if (j == i) continue;
      double d = capsule_distance(j, point);
      if (d < -1e-9 * c.radius || (d <= 1e-9 * c.radius && j < i)) {
        keep = false;
        break;
      }
    }
    if (!keep) continue;
    if (noise > 0) point += noise * c.radius * gauss(random) * normal;
    cloud.points.emplace_back(point.cast<float>());
    cloud.normals.emplace_back(normal.cast<float>());
    if (cloud.size() % 4096 == 0) progress.update(cloud.size());
  }
  return cloud;
}

nlohmann::json TubeSurface::to_json() const {
  nlohmann::json capsules = nlohmann::json::array();
  for (const auto& c : capsules_) {
    capsules.push_back({{"a", {c.a.x(), c.a.y(), c.a.z()}},
                        {"b", {c.b.x(), c.b.y(), c.b.z()}},
                        {"radius", c.radius},
                        {"open_a", c.open_a},
                        {"open_b", c.open_b}});
  }
  return {{"type", "capsule-union"}, {"capsules", capsules}};
}

TubeSurface TubeSurface::from_json(const nlohmann::json& json) {
  TubeSurface surface;
  try {
    for (const auto& c : json.at("capsules")) {
      Capsule capsule;
      for (int k = 0; k < 3; ++k) {
        capsule.a[k] = c.at("a").at(k).get<double>();
        capsule.b[k] = c.at("b").at(k).get<double>();
      }
      capsule.radius = c.at("radius").get<double>();
      capsule.open_a = c.value("open_a", false);
      capsule.open_b = c.value("open_b", false);
      surface.add(capsule);
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(std::string("bad surface description: ") + e.what());
  }
  return surface;
}

}  // namespace mcquad
