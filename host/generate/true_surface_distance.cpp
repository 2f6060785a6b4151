#include "generate/true_surface_distance.h"

#include "metrics/inward_faces.h"

namespace mcquad {

TrueSurfaceDistance measure_true_surface_distance(const QuadMesh& mesh, const TubeSurface& surface) {
  std::vector<double> absolute, relative;
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p = point_of(mesh, v);
    int capsule = surface.nearest_capsule(p);
    double d = std::abs(surface.signed_distance(p));
    absolute.push_back(d);
    relative.push_back(d / surface.capsules()[capsule].radius);
  }
  return {summarize_distances(absolute), summarize_distances(relative), inward_area_fraction(mesh, surface)};
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
          {"inward_area_fraction", d.inward_area_fraction}};
}

}  // namespace mcquad
