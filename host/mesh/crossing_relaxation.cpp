#include "mesh/crossing_relaxation.h"

#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "mesh/crossing_tracker.h"
#include "mesh/folds.h"

namespace mcquad {

constexpr int kRoundsWithoutProgress = 20;

size_t relax_crossings(QuadMesh& mesh, int rounds) {
  size_t fewest = SIZE_MAX;
  int since_fewest = 0;
  CrossingTracker crossings(mesh);  // each round smooths a few regions: look again there only
  for (int round = 0;; ++round) {
    auto pairs = crossings.pairs(mesh);
    if (pairs.size() < fewest) {
      fewest = pairs.size();
      since_fewest = 0;
    }
    // Faces pinched into one point in a tight crease, or tubes through each
    // other, are not parted by smoothing: give up.
    if (pairs.empty() || round == rounds || ++since_fewest > kRoundsWithoutProgress) return pairs.size();
    std::vector<int> faces;
    for (const auto& [a, b] : pairs) faces.insert(faces.end(), {a, b});
    std::set<int> region = corners_of(mesh, faces);
    // Smoothing only the crossing faces' corners pulls them into their
    // neighbours; their rings give way with them.
    grow_region(mesh, region, 1 + std::min(5, round / 10));
    relax_vertices(mesh, region);
  }
}

}  // namespace mcquad
