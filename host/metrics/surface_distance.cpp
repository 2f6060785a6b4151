#include "metrics/surface_distance.h"

#include <algorithm>
#include <cmath>

#include "core/shared_math.h"
#include "mesh/face_intersections.h"
#include "mesh/triangle_neighbourhoods.h"
#include "mesh/triangle_tree.h"

namespace mcquad {

DistanceSummary summarize_distances(std::vector<double> distances) {
  DistanceSummary s;
  if (distances.empty()) return s;
  double sum = 0;
  for (double d : distances) sum += d;
  s.mean = sum / distances.size();
  size_t k = std::min(distances.size() - 1, size_t(std::ceil(0.95 * distances.size())) - 1);
  std::nth_element(distances.begin(), distances.begin() + k, distances.end());
  s.p95 = distances[k];
  s.max = *std::max_element(distances.begin(), distances.end());
  return s;
}

nlohmann::json to_json(const DistanceSummary& d) { return {{"mean", d.mean}, {"p95", d.p95}, {"max", d.max}}; }

std::vector<double> mesh_to_cloud_distances(const QuadMesh& mesh, const CellTree& cells) {
  std::vector<double> out(mesh.n_vertices());
  // Host-side measurements use every core (the serial backend stays serial).
#pragma omp parallel for schedule(static)
  for (long i = 0; i < long(mesh.n_vertices()); ++i) {
    const auto& p = mesh.point(QuadMesh::VertexHandle(int(i)));
    float distance2 = 0;
    device::mcq_nearest_point_cell(cells.node_bounds.data(), cells.node_children.data(), cells.cell_offsets.data(),
                                   cells.points.data(), cells.bounds_inset,
                                   device::mcq_make_vec3(float(p[0]), float(p[1]), float(p[2])), -1, &distance2);
    out[size_t(i)] = std::sqrt(double(distance2));
  }
  return out;
}

std::vector<double> cloud_to_mesh_distances(const QuadMesh& mesh, const PointCloud& cloud, size_t max_points) {
  MeshTriangles triangles = triangulate(mesh);
  TriangleTree tree(triangles);
  size_t stride = cloud_sample_stride(cloud.size(), max_points);
  std::vector<double> out((cloud.size() + stride - 1) / stride);
  TriangleNeighbourhoods neighbourhoods(tree, out.size());
  // Each thread takes a run of points, near each other where the cloud is
  // sorted spatially (as fit sorts it): the neighbours of the last answer
  // are most often all the next point needs to test.
#pragma omp parallel
  {
    long hint = -1;
#pragma omp for schedule(static)
    for (long i = 0; i < long(out.size()); ++i) {
      auto [distance, triangle] = neighbourhoods.nearest(cloud.points[size_t(i) * stride].cast<double>(), hint);
      out[size_t(i)] = distance;
      hint = triangle;
    }
  }
  return out;
}

}  // namespace mcquad
