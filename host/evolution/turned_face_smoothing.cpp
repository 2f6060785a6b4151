#include "evolution/turned_face_smoothing.h"

#include <algorithm>
#include <set>

#include "evolution/deep_vertex_push.h"
#include "evolution/evolve.h"
#include "mesh/crossing_guard.h"
#include "mesh/folds.h"

namespace mcquad {
namespace {

//! The faces the smoothing turns out: turned as a whole (ScanOrientation::FaceTest).
constexpr ScanOrientation::FaceTest kTurned = ScanOrientation::FaceTest::kWhole;

//! The faces round the given vertices: the only ones a move of them turns.
std::vector<int> faces_round(const QuadMesh& mesh, const std::set<int>& vertices) {
  std::vector<int> faces;
  for (int v : vertices)
    for (auto f : mesh.vf_range(mesh.vertex_handle(v))) faces.push_back(f.idx());
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

}  // namespace

TurnedFaceSmoothing smooth_turned_faces(QuadMesh& mesh, const MeshArrays& start, const ScanOrientation& scan,
                                        int rounds) {
  TurnedFaceSmoothing result;
  if (scan.empty()) return result;
  std::vector<int> turned = scan.inward_faces(mesh, nullptr, kTurned);
  result.faces_before = result.faces_after = turned.size();
  result.area_before = result.area_after = area_fraction(mesh, turned);
  if (turned.empty() || rounds <= 0) return result;
  CrossingGuard guard(start);
  std::vector<float> before = mesh_positions(mesh);
  for (; result.rounds < rounds && !turned.empty(); ++result.rounds) {
    std::set<int> corners = corners_of(mesh, turned);
    relax_vertices(mesh, corners);
    std::vector<float> after = before;
    for (int v : corners)
      for (int k = 0; k < 3; ++k) after[3 * size_t(v) + size_t(k)] = float(mesh.point(mesh.vertex_handle(v))[k]);
    guard.apply(before, after);
    // The guard's shortened moves, back into the mesh (the float positions
    // are the evolution's; the mesh then holds exactly what is written).
    for (int v : corners)
      mesh.set_point(mesh.vertex_handle(v),
                     QuadMesh::Point(after[3 * size_t(v)], after[3 * size_t(v) + 1], after[3 * size_t(v) + 2]));
    bool moved = after != before;
    before.swap(after);
    std::vector<int> around = faces_round(mesh, corners);
    turned = scan.inward_faces(mesh, &around, kTurned);
    if (!moved) break;
  }
  result.faces_after = turned.size();
  result.area_after = area_fraction(mesh, turned);
  return result;
}

namespace {

//! Smoothing, settling, smoothing again (turn_faces_out without the push).
TurnedFaceSmoothing smooth_and_settle(EvolutionBackend& backend, const MeshArrays& start,
                                      const EvolutionParameters& parameters, const ScanOrientation& scan,
                                      QuadMesh& mesh, unsigned first_iteration) {
  const int rounds = int(parameters.turned_face_rounds);
  TurnedFaceSmoothing result = smooth_turned_faces(mesh, start, scan, rounds);
  if (result.rounds == 0) return result;
  settle_onto_cloud(backend, start, parameters, mesh, first_iteration, kSettleIterations);
  TurnedFaceSmoothing again = smooth_turned_faces(mesh, start, scan, rounds);
  result.settle_iterations = kSettleIterations;
  result.rounds += again.rounds;
  result.faces_after = again.faces_after;
  result.area_after = again.area_after;
  return result;
}

}  // namespace

TurnedFaceSmoothing turn_faces_out(EvolutionBackend& backend, const MeshArrays& start,
                                   const EvolutionParameters& parameters, const ScanOrientation& scan, QuadMesh& mesh,
                                   unsigned first_iteration) {
  // No evolution asked for (--iterations 0), no push: it would fit the mesh anyway.
  if (!parameters.push_deep || parameters.iterations == 0)
    return smooth_and_settle(backend, start, parameters, scan, mesh, first_iteration);
  QuadMesh pushed = mesh;
  TurnedFaceSmoothing plain = smooth_and_settle(backend, start, parameters, scan, mesh, first_iteration);
  const int push_rounds = push_deep_vertices(pushed, start, scan, kDeepVertexDepth * parameters.epsilon,
                                             int(parameters.turned_face_rounds));
  plain.deep_push_rounds = push_rounds;
  if (push_rounds == 0) return plain;
  settle_onto_cloud(backend, start, parameters, pushed, first_iteration, kSettleIterations);
  TurnedFaceSmoothing result =
      smooth_and_settle(backend, start, parameters, scan, pushed, first_iteration + kSettleIterations);
  if (scan.inward_area_fraction(pushed) > scan.inward_area_fraction(mesh)) return plain;
  result.faces_before = plain.faces_before;  // as the evolution left them, before the push
  result.area_before = plain.area_before;
  result.settle_iterations += kSettleIterations;
  result.deep_push_rounds = push_rounds;
  result.deep_push_kept = true;
  mesh = std::move(pushed);
  return result;
}

}  // namespace mcquad
