#include "pipeline/skeleton_extraction.h"

#include <chrono>

#include "io/point_cloud_io.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

nlohmann::json skeleton_report(const ExtractedSkeleton& extracted, const std::string& points_name, double seconds) {
  SkeletonGraph graph = build_skeleton_graph(extracted.skeleton, "the skeleton extracted from " + points_name, 0.0);
  nlohmann::json nodes = nlohmann::json::array();
  int junctions = 0, ends = 0;
  for (size_t v = 0; v < extracted.skeleton.nodes.size(); ++v) {
    const Eigen::Vector3d& p = extracted.skeleton.nodes[v];
    NodeKind kind = graph.kind(int(v));
    junctions += kind == NodeKind::kJunction;
    ends += kind == NodeKind::kEnd;
    nodes.push_back({{"position", {p.x(), p.y(), p.z()}},
                     {"radius", extracted.radii[v]},
                     {"kind", kind == NodeKind::kEnd ? "end" : kind == NodeKind::kJunction ? "junction" : "regular"},
                     {"degree", graph.degree(int(v))}});
  }
  int cycles = 0;
  for (int c = 0; c < graph.component_count; ++c) cycles += graph.independent_cycles(c);
  return {{"points", points_name},
          {"nodes", nodes},
          {"bones", extracted.skeleton.edges.size()},
          {"junctions", junctions},
          {"ends", ends},
          {"independent_cycles", cycles},
          {"components", graph.component_count},
          {"voxel_size", extracted.voxel_size},
          {"voxels", extracted.voxels},
          {"discarded_voxels", extracted.discarded_voxels},
          {"seconds", seconds}};
}

ExtractedSkeleton extract_skeleton_timed(const PointCloud& cloud, const std::string& name,
                                         const SkeletonExtractionOptions& options, double& seconds) {
  auto start = std::chrono::steady_clock::now();
  ExtractedSkeleton extracted = extract_skeleton(cloud, name, options);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return extracted;
}

ExtractedSkeleton extract_skeleton_from_file(const std::string& points_path, const SkeletonExtractionOptions& options,
                                             double& seconds) {
  return extract_skeleton_timed(read_point_cloud(points_path), points_path, options, seconds);
}

}  // namespace mcquad
