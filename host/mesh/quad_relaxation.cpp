#include "mesh/quad_relaxation.h"

#include <algorithm>
#include <set>
#include <vector>

#include "mesh/crossing_tracker.h"
#include "mesh/folds.h"
#include "mesh/quad_shape.h"

namespace mcquad {
namespace {

constexpr int kRoundsWithoutProgress = 10;

//! The scaled Jacobian of face `f` if it is a quad; 1 (nothing to relax) if not.
double quad_jacobian(const QuadMesh& mesh, QuadMesh::FaceHandle f) {
  std::vector<Eigen::Vector3d> corners = face_corners(mesh, f);
  return corners.size() == 4 ? scaled_jacobian(corners.data()) : 1.0;
}

std::vector<int> poor_quads(const QuadMesh& mesh, double least) {
  std::vector<int> poor;
  for (auto f : mesh.faces())
    if (quad_jacobian(mesh, f) < least) poor.push_back(f.idx());
  return poor;
}

//! The least scaled Jacobian of the quads round `v`.
double least_around(const QuadMesh& mesh, QuadMesh::VertexHandle v) {
  double least = 1;
  for (auto f : mesh.vf_range(v)) least = std::min(least, quad_jacobian(mesh, f));
  return least;
}

//! Folded edges among the edges of the faces round `v` (some counted twice).
size_t folds_around(const QuadMesh& mesh, QuadMesh::VertexHandle v) {
  size_t folds = 0;
  for (auto f : mesh.vf_range(v))
    for (auto e : mesh.fe_range(f)) folds += is_folded(mesh, e);
  return folds;
}

//! One round of moving each poor quad's corners toward where they would
//! make it a parallelogram (a + c - d for corner v between a and c, d
//! opposite), the whole way, half or a quarter, whichever first raises the
//! least scaled Jacobian of the quads round v and folds none of their
//! edges. Returns whether any moved.
bool straighten_poor_corners(QuadMesh& mesh, const std::vector<int>& poor) {
  bool moved = false;
  for (int f : poor) {
    std::vector<QuadMesh::VertexHandle> corner;
    for (auto v : mesh.fv_range(mesh.face_handle(f))) corner.push_back(v);
    if (corner.size() != 4) continue;
    for (size_t k = 0; k < 4; ++k) {
      const QuadMesh::VertexHandle v = corner[k];
      const QuadMesh::Point p = mesh.point(v);
      const QuadMesh::Point target =
          mesh.point(corner[(k + 1) % 4]) + mesh.point(corner[(k + 3) % 4]) - mesh.point(corner[(k + 2) % 4]);
      const double before = least_around(mesh, v);
      const size_t folds = folds_around(mesh, v);
      for (double step : {1.0, 0.5, 0.25}) {
        mesh.set_point(v, p + step * (target - p));
        if (least_around(mesh, v) > before + 1e-6 && folds_around(mesh, v) <= folds) {
          moved = true;
          break;
        }
        mesh.set_point(v, p);
      }
    }
  }
  return moved;
}

}  // namespace

size_t relax_poor_quads(QuadMesh& mesh, double least, int rounds) {
  std::vector<int> poor = poor_quads(mesh, least);
  if (poor.empty()) return 0;
  CrossingTracker tracker(mesh);  // each round smooths round the poor quads: look again there only
  const size_t crossings = tracker.pairs(mesh).size(), folds = folded_edges(mesh);
  size_t fewest = poor.size();
  int since_fewest = 0;
  // Runs `move` (which says whether it moved anything) and undoes it where
  // it left faces crossing or folded that were not before.
  auto kept_unless_worse = [&](auto&& move) {
    std::vector<QuadMesh::Point> kept;  // relax_folds may move vertices beyond the poor quads
    for (auto v : mesh.vertices()) kept.push_back(mesh.point(v));
    if (!move()) return false;
    if (tracker.pairs(mesh).size() <= crossings && folded_edges(mesh) <= folds) return true;
    for (auto v : mesh.vertices()) mesh.set_point(v, kept[size_t(v.idx())]);
    return false;
  };
  // Each poor quad's corners and their ring are smoothed; where that makes
  // faces cross, the corners alone; where even that does, nothing more.
  auto smooth = [&](int rings) {
    return kept_unless_worse([&] {
      std::set<int> region = corners_of(mesh, poor);
      grow_region(mesh, region, rings);
      relax_vertices(mesh, region);
      if (folded_edges(mesh) > folds) relax_folds(mesh);
      return true;
    });
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
  // What smoothing leaves (a corner near 180 degrees beside a junction's
  // irregular vertex, where the neighbours' mean is no better): the corners
  // moved toward a parallelogram, round by round, until a round moves none
  // or makes faces cross or fold (that round undone).
  for (int round = 0; round < rounds && !poor.empty(); ++round) {
    if (!kept_unless_worse([&] { return straighten_poor_corners(mesh, poor); })) break;
    poor = poor_quads(mesh, least);
  }
  return poor.size();
}

}  // namespace mcquad
