#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "mesh/close_triangle_pairs.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {

//! What a device needs to test a step as CrossingGuard::apply would
//! (kernels/guard.cl): the mesh's triangles, the guard's close pairs and
//! their reference positions, the pairs of faces across an edge, the faces'
//! initial normals and their Jacobian floors.
struct GuardArrays {
  std::vector<uint32_t> triangle_corners;  //!< 3 a triangle (each quad split along its 0-2 diagonal)
  std::vector<uint32_t> close_pairs;       //!< 2 a pair of triangles
  std::vector<float> references;           //!< 3 a vertex
  double move_limit = 0;                   //!< CloseTrianglePairs::move_limit
  std::vector<uint32_t> fold_pairs;        //!< 2 a pair of faces, lower first
  std::vector<float> initial_normals;      //!< 3 a face, unit
  std::vector<double> jacobian_floors;     //!< 1 a face
};

//! Robust mode's guard against self-intersection and inverted faces, run on
//! the host after a step (docs/DESIGN.md; evolution/guarded_steps.h skips it
//! where a device's test of the step finds nothing). The per-vertex fold
//! guard sees only a vertex's own faces for one step; faces that are not
//! neighbours can still pass through each other (two sides of a crease
//! moving into it, a vertex pulled across a thin neck), and small turns add
//! up over steps. After a step the guard looks for new defects, by the same
//! tests `mcquad metrics` counts:
//!   - face pairs that cross (mesh/face_intersections.h);
//!   - edges whose two faces fold over each other (normals more than 120
//!     degrees apart);
//!   - faces turned more than 90 degrees from where they started (into the
//!     tube);
//!   - quads whose scaled Jacobian falls below kLeastScaledJacobian, or below
//!     the lowest value they have had when they started under it.
//! Of a new crossing or fold, the face whose corners moved further gives way:
//! its moved corners take half their step, then a quarter, an eighth, then
//! none, until no new defect is left; a turned or badly shaped quad gives
//! way alone. So a mesh without defects keeps none, and vertices held back
//! still move as far as they can. Crossings and folds already there before
//! the step are left alone (and stay counted, not hidden).
class CrossingGuard {
 public:
  //! `mesh` (topology and starting positions) must outlive the guard.
  explicit CrossingGuard(const MeshArrays& mesh);

  //! Shortens the moves from `before` to `after` (both as the mesh's
  //! positions) as above; returns the vertices held back, in order.
  std::vector<uint32_t> apply(const std::vector<float>& before, std::vector<float>& after);

  //! Whether the positions last accepted have no crossing or fold: then a
  //! step in which a device finds none of the defects above (GuardArrays)
  //! is one apply() would leave as it is, but for raising the floors.
  bool knows_no_defects() const { return known_.empty(); }
  //! What a device needs to test the next steps (GuardArrays).
  GuardArrays device_arrays() const;
  //! Changes whenever the close pairs or their references change (then the
  //! device needs device_arrays() again; otherwise the floors alone).
  size_t close_pairs_version() const { return close_pairs_.builds() + close_pairs_.refreshes() + (widenings_ << 32); }
  //! Doubles the close pairs' gap and makes the list again at the positions
  //! apply() last accepted: a list that lasts more steps, of more pairs. Only as far as
  //! 2^kMostWidenings times the first gap; returns whether it widened.
  bool widen_close_pairs();
  static constexpr int kMostWidenings = 2;
  const std::vector<double>& jacobian_floors() const { return jacobian_floor_; }
  //! Picks up after steps a device accepted without the host: `before` as
  //! the positions last accepted and `floors` as raised since. Only while
  //! knows_no_defects().
  void resume(const std::vector<float>& before, const std::vector<double>& floors);

  //! A defect: two faces (a < b), or one turned face (b = -1).
  using Defect = std::pair<int, int>;
  //! Quads whose worst corner falls below this scaled Jacobian count as
  //! defects (mesh/quad_shape.h): a corner near 180 degrees or beyond.
  static constexpr double kLeastScaledJacobian = 0.3;
  //! The defects of the mesh at `positions`, sorted; with `only_faces`,
  //! those involving at least one of those faces (at a cost in those faces,
  //! not in the mesh: the later rounds of apply look at a few faces).
  std::vector<Defect> defects(const std::vector<float>& positions, const std::vector<char>* only_faces = nullptr) const;

 private:
  const MeshArrays& mesh_;
  //! Per face, the faces across its edges: those of face f are
  //! neighbours_[neighbour_offsets_[f] .. neighbour_offsets_[f + 1]).
  std::vector<uint32_t> neighbour_offsets_, neighbours_;
  //! The mesh's triangles (mesh/face_intersections.h), their positions those
  //! apply tests.
  MeshTriangles triangles_;
  std::vector<float> initial_normals_;  //!< per face, unit
  std::vector<Defect> known_;           //!< face pairs crossing or folded at known_at_
  std::vector<float> known_at_;         //!< the positions known_ holds for
  std::vector<double> jacobian_floor_;  //!< per face: the least scaled Jacobian it may take
  std::vector<uint32_t> low_faces_;     //!< faces whose floor is still under kLeastScaledJacobian
  //! The crossing test's broad phase, kept from call to call while the
  //! vertices stay near (a cache: defects() gives the same answers without).
  mutable CloseTrianglePairs close_pairs_;
  size_t widenings_ = 0;  //!< times widen_close_pairs() doubled the gap

  //! Floors rise with the quads, up to kLeastScaledJacobian.
  void raise_jacobian_floors(const std::vector<float>& positions);
  //! defects() on `triangles`, which hold `positions`.
  std::vector<Defect> find_defects(const MeshTriangles& triangles, const std::vector<float>& positions,
                                   const std::vector<char>* only_faces) const;
  //! The crossing face pairs `found` (of the faces tested), with the folds,
  //! turned faces and poorly shaped quads among the faces tested, sorted.
  std::vector<Defect> with_shape_defects(std::vector<Defect> found, const std::vector<float>& positions,
                                         const std::vector<char>* only_faces) const;
};

}  // namespace mcquad
