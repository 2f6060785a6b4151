#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace mcquad {

//! Points with the scan's own outward normals: what a fitted mesh's
//! orientation is judged against. A strided sample keeps the memory small
//! on huge clouds while pinning the fraction of faces down.
struct OrientedSample {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  //!< unit, one per point
  bool empty() const { return points.empty(); }
};

//! Adds p with its normal n, unit length, when n is usable (finite, not
//! zero: generated outliers and some scanners' unknowns carry zero normals).
void add_oriented_point(OrientedSample& sample, const Eigen::Vector3f& p, const Eigen::Vector3f& n);

//! An unorganized point cloud. Positions are float (what the device uses and
//! what scanners deliver); normals are optional and never required.
struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Vector3f> normals;  //!< empty, or one per point
  //! A strided sample of the points with their normals, when a reader was
  //! asked for one instead of every normal (read_point_cloud).
  OrientedSample oriented;

  size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  //! Flat x,y,z array view of the points (Eigen::Vector3f is three packed floats).
  const float* data() const { return reinterpret_cast<const float*>(points.data()); }
};

//! The stride k for which every k-th of `points` points gives at most
//! `max_points` of them (1 when max_points is 0: every point).
size_t cloud_sample_stride(size_t points, size_t max_points);

//! Every k-th point (with its normal, when the cloud has normals), at most
//! `max_points` of them. On a spatially sorted cloud (sort_spatially) the
//! sample is spread evenly over the surface.
PointCloud strided_sample(const PointCloud& cloud, size_t max_points);

//! Every k-th point with a usable normal (finite, nonzero), at most about
//! `max_points` of them; empty when the cloud has no normals.
OrientedSample oriented_sample(const PointCloud& cloud, size_t max_points = 1000000);

//! Reorders the points along a Morton (Z-order) curve, so that points near in
//! space are near in memory: every kd-tree built and searched afterwards
//! touches far fewer cache lines. Scans come in arbitrary order, and no
//! stage needs the original one.
void sort_spatially(PointCloud& cloud);
//! The same for a sample of oriented points, in place.
void sort_spatially(OrientedSample& sample);

//! InputError naming `name` for a cloud a fit cannot start from: empty, a
//! non-finite coordinate (the first one's index given), or normals that are
//! not one per point. The readers check as they read; this is for clouds
//! made in memory.
void check_point_cloud(const PointCloud& cloud, const std::string& name);

//! Axis-aligned bounding box of a cloud (min, max); zero box for an empty one.
std::pair<Eigen::Vector3f, Eigen::Vector3f> bounding_box(const PointCloud& cloud);

}  // namespace mcquad
