#include "generate/true_surface_distance.h"

#include "metrics/inward_faces.h"

namespace mcquad {

TrueSurfaceDistance measure_true_surface_distance(const QuadMesh& mesh, const TubeSurface& surface) {
  std::vector<double> absolute, relative;
  double signed_sum = 0;
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p = point_of(mesh, v);
    double radius = surface.capsules()[size_t(surface.nearest_capsule(p))].radius;
    double d = surface.signed_distance(p);
    absolute.push_back(std::abs(d));
    relative.push_back(std::abs(d) / radius);
    signed_sum += d / radius;
  }
  TrueSurfaceDistance out;
  out.absolute = summarize_distances(absolute);
  out.relative = summarize_distances(relative);
  out.signed_relative_mean = relative.empty() ? 0.0 : signed_sum / double(relative.size());
  out.inward_area_fraction = inward_area_fraction(mesh, surface);
  return out;
}

double inward_area_fraction(const QuadMesh& mesh, const TubeSurface& surface) {
  std::vector<int> inward;
  for (auto f : mesh.faces()) {
    Eigen::Vector3d centre = face_centroid(mesh, f.idx());
    // Central differences at a step far below any radius the shapes have.
    double h = 1e-5 * surface.capsules()[size_t(surface.nearest_capsule(centre))].radius;
    Eigen::Vector3d gradient;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d step = Eigen::Vector3d::Unit(k) * h;
      gradient[k] = surface.signed_distance(centre + step) - surface.signed_distance(centre - step);
    }
    if (face_vector_area(mesh, f).dot(gradient) < 0) inward.push_back(f.idx());
  }
  return area_fraction(mesh, inward);
}

DistanceSummary cloud_to_mesh_relative_to_local_radius(const QuadMesh& mesh, const PointCloud& cloud,
                                                       const TubeSurface& surface) {
  std::vector<double> relative = cloud_to_mesh_distances(mesh, cloud);
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(relative.size()); ++i)
    relative[size_t(i)] /= surface.capsules()[surface.nearest_capsule(cloud.points[size_t(i)].cast<double>())].radius;
  return summarize_distances(relative);
}

nlohmann::json to_json(const TrueSurfaceDistance& d) {
  return {{"absolute", to_json(d.absolute)},
          {"relative_to_radius", to_json(d.relative)},
          {"signed_mean_relative_to_radius", d.signed_relative_mean},
          {"inward_area_fraction", d.inward_area_fraction}};
}

}  // namespace mcquad
