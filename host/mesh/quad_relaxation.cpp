#include "mesh/quad_relaxation.h"

#include <set>
#include <vector>

#include "mesh/crossing_tracker.h"
#include "mesh/folds.h"
#include "mesh/quad_shape.h"

namespace mcquad {
namespace {

constexpr int kRoundsWithoutProgress = 10;

std::vector<int> poor_quads(const QuadMesh& mesh, double least) {
  std::vector<int> poor;
  for (auto f : mesh.faces()) {
    std::vector<Eigen::Vector3d> corners = face_corners(mesh, f);
    if (corners.size() == 4 && scaled_jacobian(corners.data()) < least) poor.push_back(f.idx());
  }
  return poor;
}

}  // namespace

size_t relax_poor_quads(QuadMesh& mesh, double least, int rounds) {
  std::vector<int> poor = poor_quads(mesh, least);
  if (poor.empty()) return 0;
  CrossingTracker tracker(mesh);  // each round smooths round the poor quads: look again there only
  const size_t crossings = tracker.pairs(mesh).size(), folds = folded_edges(mesh);
  size_t fewest = poor.size();
  int since_fewest = 0;
  // Each poor quad's corners and their ring are smoothed; where that makes
  // faces cross, the corners alone; where even that does, nothing more.
  auto smooth = [&](int rings) {
    std::set<int> region = corners_of(mesh, poor);
    grow_region(mesh, region, rings);
    std::vector<QuadMesh::Point> kept;  // relax_folds may move vertices beyond the region
    for (auto v : mesh.vertices()) kept.push_back(mesh.point(v));
    relax_vertices(mesh, region);
    if (folded_edges(mesh) > folds) relax_folds(mesh);
    if (tracker.pairs(mesh).size() <= crossings && folded_edges(mesh) <= folds) return true;
    for (auto v : mesh.vertices()) mesh.set_point(v, kept[size_t(v.idx())]);
    return false;
  };
  for (int round = 0; round < rounds && !poor.empty() && since_fewest < kRoundsWithoutProgress; ++round) {
    if (!smooth(1) && !smooth(0)) break;
    poor = poor_quads(mesh, least);
    if (poor.size() < fewest) {
      fewest = poor.size();
      since_fewest = 0;
    } else {
      ++since_fewest;
    }
  }
  return poor.size();
}

}  // namespace mcquad
