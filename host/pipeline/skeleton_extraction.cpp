#include "pipeline/skeleton_extraction.h"

#include <chrono>

#include "io/point_cloud_io.h"

namespace mcquad {

SkeletonReport skeleton_report(const ExtractedSkeleton& extracted, const std::string& points_name, double seconds) {
  SkeletonGraph graph = build_skeleton_graph(extracted.skeleton, "the skeleton extracted from " + points_name, 0.0);
  SkeletonReport report;
  report.points = points_name;
  report.positions = extracted.skeleton.nodes;
  report.radii = extracted.radii;
  for (size_t v = 0; v < extracted.skeleton.nodes.size(); ++v) {
    NodeKind kind = graph.kind(int(v));
    report.kinds.push_back(kind);
    report.degrees.push_back(graph.degree(int(v)));
    report.junctions += kind == NodeKind::kJunction;
    report.ends += kind == NodeKind::kEnd;
  }
  for (int c = 0; c < graph.component_count; ++c) report.independent_cycles += graph.independent_cycles(c);
  report.bones = extracted.skeleton.edges.size();
  report.components = graph.component_count;
  report.voxel_size = extracted.voxel_size;
  report.voxels = extracted.voxels;
  report.discarded_voxels = extracted.discarded_voxels;
  report.seconds = seconds;
  return report;
}

nlohmann::json to_json(const SkeletonReport& r) {
  nlohmann::json nodes = nlohmann::json::array();
  for (size_t v = 0; v < r.positions.size(); ++v) {
    const Eigen::Vector3d& p = r.positions[v];
    NodeKind kind = r.kinds[v];
    nodes.push_back({{"position", {p.x(), p.y(), p.z()}},
                     {"radius", r.radii[v]},
                     {"kind", kind == NodeKind::kEnd        ? "end"
                              : kind == NodeKind::kJunction ? "junction"
                                                            : "regular"},
                     {"degree", r.degrees[v]}});
  }
  nlohmann::json dropped = nlohmann::json::array();
  for (const auto& limb : r.dropped_limbs)
    dropped.push_back({{"end", {limb.end.x(), limb.end.y(), limb.end.z()}},
                       {"overlap", {limb.overlap.x(), limb.overlap.y(), limb.overlap.z()}}});
  return {{"points", r.points},
          {"nodes", nodes},
          {"dropped_limbs", dropped},
          {"bones", r.bones},
          {"junctions", r.junctions},
          {"ends", r.ends},
          {"independent_cycles", r.independent_cycles},
          {"components", r.components},
          {"voxel_size", r.voxel_size},
          {"voxels", r.voxels},
          {"discarded_voxels", r.discarded_voxels},
          {"seconds", r.seconds}};
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
