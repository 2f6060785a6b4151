#include "skeleton/bone_assignment.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "core/point_index.h"
#include "core/point_text.h"
#include "skeleton/acute_junctions.h"
#include "skeleton/nearest_bone.h"

namespace mcquad {
namespace {

double median(std::vector<float>& values) {
  if (values.empty()) return 0.0;
  auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

//! Bones inside a thick body (a torso, a palm) may be nearer to no cloud
//! point than other bones are, so no point picks them. Their radius is the
//! cloud's distance from them instead: the median over samples along the
//! bone of the distance to the nearest point, the radius of the largest
//! tube inside the body around the bone. A bone that far from the cloud
//! compared with every bone that has points lies outside it: InputError.
void radii_of_bones_without_points(const SkeletonGraph& graph, const std::vector<size_t>& point_count,
                                   const PointIndex<float>& cloud_index, const std::string& source,
                                   std::vector<double>& bone_radius) {
  double largest_with_points = 0;
  for (size_t b = 0; b < bone_radius.size(); ++b)
    if (point_count[b] > 0) largest_with_points = std::max(largest_with_points, bone_radius[b]);
  constexpr int kSamples = 9;
  for (size_t b = 0; b < bone_radius.size(); ++b) {
    if (point_count[b] > 0) continue;
    const Eigen::Vector3d& a = graph.positions[graph.edges[b][0]];
    const Eigen::Vector3d& c = graph.positions[graph.edges[b][1]];
    std::vector<float> gaps;
    for (int k = 1; k <= kSamples; ++k) {
      Eigen::Vector3d p = a + (c - a) * (double(k) / (kSamples + 1));
      gaps.push_back(std::sqrt(cloud_index.nearest(p.cast<float>()).second));
    }
    bone_radius[b] = median(gaps);
    if (bone_radius[b] > 2.0 * largest_with_points) {
      std::ostringstream s;
      s << source << ": bone between nodes at " << point_text(a) << " and " << point_text(c)
        << " has no cloud points near it and lies " << bone_radius[b]
        << " from the cloud, more than twice the largest radius of the other bones (" << largest_with_points
        << "): the skeleton does not match the cloud";
      throw InputError(s.str());
    }
  }
}

}  // namespace

std::vector<double> widest_bone_radii(size_t node_count, const std::vector<std::array<int, 2>>& edges,
                                      const std::vector<double>& bone_radius) {
  std::vector<double> widest(node_count, 0.0);
  for (size_t b = 0; b < edges.size(); ++b)
    for (int end : edges[b]) widest[size_t(end)] = std::max(widest[size_t(end)], bone_radius[b]);
  return widest;
}

double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double* t) {
  Eigen::Vector3d ab = b - a;
  double length2 = ab.squaredNorm();
  double s = length2 > 0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  if (t) *t = s;
  return (p - (a + s * ab)).norm();
}

BoneAssignment assign_points_to_bones(const SkeletonGraph& graph, const PointCloud& cloud, const std::string& source,
                                      const PointIndex<float>* cloud_index) {
  NearestBone nearest_bone(graph);
  size_t bone_count = graph.edges.size();

  BoneAssignment result;
  size_t n = cloud.size();
  result.bone.resize(n);
  result.parameter.resize(n);
  result.distance.resize(n);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(n); ++i) {
    NearestBone::Hit hit = nearest_bone.find(cloud.points[i].cast<double>());
    result.bone[i] = hit.bone;
    result.parameter[i] = float(hit.parameter);
    result.distance[i] = float(hit.distance);
  }

  // A bone's radius: the median distance of its interior points (those that
  // project inside it), or of all its points when fewer than 8 are
  // interior. Counted first so each bone's list is allocated once, exactly:
  // at 10^7 points grown lists would double the memory of this stage.
  auto interior = [&](size_t i) { return result.parameter[i] > 0.0f && result.parameter[i] < 1.0f; };
  std::vector<size_t> interior_count(bone_count, 0), all_count(bone_count, 0);
  for (size_t i = 0; i < n; ++i) {
    all_count[size_t(result.bone[i])] += 1;
    interior_count[size_t(result.bone[i])] += interior(i);
  }
  std::vector<std::vector<float>> distances(bone_count);
  for (size_t b = 0; b < bone_count; ++b)
    distances[b].reserve(interior_count[b] >= 8 ? interior_count[b] : all_count[b]);
  for (size_t i = 0; i < n; ++i) {
    size_t b = size_t(result.bone[i]);
    if (interior_count[b] < 8 || interior(i)) distances[b].push_back(result.distance[i]);
  }
  result.bone_radius.resize(bone_count);
  for (size_t b = 0; b < bone_count; ++b) result.bone_radius[b] = median(distances[b]);
  std::vector<std::vector<float>>().swap(distances);

  std::unique_ptr<PointIndex<float>> own_index;
  if (!cloud_index) cloud_index = (own_index = std::make_unique<PointIndex<float>>(cloud.points)).get();
  radii_of_bones_without_points(graph, all_count, *cloud_index, source, result.bone_radius);

  result.node_radius = node_radii(graph, result.bone_radius);

  // Radii as large as the cloud itself: the bones lie outside it.
  auto [lo, hi] = bounding_box(cloud);
  double diagonal = double((hi - lo).norm());
  for (size_t b = 0; b < bone_count; ++b) {
    if (result.bone_radius[b] > 0.5 * diagonal)
      throw InputError(source + ": the cloud lies " + std::to_string(result.bone_radius[b]) +
                       " from its bones on average, half its own size: the skeleton does not match the cloud");
  }
  // A node far from every cloud point lies outside the cloud. Judged by the
  // widest of its bones (node_radius, a junction's thinnest bone, refused a
  // thin branch's junction: 0.99 from the cloud against a branch radius of
  // 0.22).
  const std::vector<double> widest = widest_bone_radii(graph.node_count(), graph.edges, result.bone_radius);
  for (size_t v = 0; v < graph.node_count(); ++v) {
    double gap = std::sqrt(double(cloud_index->nearest(graph.positions[v].cast<float>()).second));
    if (gap > 3.0 * widest[v] + 1e-12) {
      std::ostringstream s;
      s << source << ": skeleton node " << v + 1 << " at " << point_text(graph.positions[v]) << " is " << gap
        << " from the nearest cloud point, far outside the cloud (local radius " << widest[v] << ")";
      throw InputError(s.str());
    }
  }
  // Most points far from every bone: the skeleton belongs to another shape.
  size_t far = 0;
  for (size_t i = 0; i < n; ++i) far += result.distance[i] > 3.0 * result.bone_radius[result.bone[i]];
  if (far > n / 5) {
    throw InputError(source + ": " + std::to_string(100 * far / n) +
                     "% of the cloud lies far from every bone: the skeleton does not match the cloud");
  }
  return result;
}

}  // namespace mcquad
