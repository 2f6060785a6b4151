#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "mesh/face_intersections.h"
#include "mesh/triangle_tree.h"

namespace mcquad {

//! The intersecting face pairs of one mesh as its vertices move, step after
//! step, without a new broad phase each time: a Verlet list, as molecular
//! dynamics keeps for pairs of atoms. Every vertex has a reference position;
//! the list holds the triangle pairs (sharing no vertex, of different faces)
//! whose boxes are within `gap` per axis at the reference positions. While
//! no vertex has moved more than about gap / 2 along any axis from its own
//! reference, every pair whose boxes overlap now is on the list, so testing
//! the list finds exactly what intersecting_face_pairs finds. The vertices
//! that have gone further (and with them those half way there) take their
//! positions as new references and only their triangles' pairs are looked
//! for again (the smoothing of a few turned faces, or the held-back
//! vertices of a fine mesh, move a few vertices far while the rest stay),
//! in the tree of the whole list's build refitted to the new references;
//! when they are many, the whole list is built again. On the knot's mesh most of the evolution's steps move every
//! vertex far less than that (docs/PERFORMANCE.md).
class CloseTrianglePairs {
 public:
  explicit CloseTrianglePairs(double gap) : gap_(gap) {}

  //! The gap the list was made for.
  double gap() const { return gap_; }

  //! The usual gap: half the triangles' mean edge length. The list then
  //! holds about a triangle's ring of neighbours, and its pairs last while
  //! the vertices move less than a quarter of an edge (docs/PERFORMANCE.md).
  static double half_mean_edge(const MeshTriangles& triangles);

  //! As intersecting_face_pairs(triangles, only_faces); every call's
  //! triangles must have the same corners (one mesh), positions may differ.
  //! With `only_faces` the test costs in the pairs of those faces' triangles
  //! (the crossing guard's later rounds look at a few faces of a large mesh).
  std::vector<std::pair<int, int>> intersecting_face_pairs(const MeshTriangles& triangles,
                                                           const std::vector<char>* only_faces = nullptr);

  //! The listed pairs, each once (its lower triangle first), 2 a pair: what
  //! a device tests (kernels/guard.cl).
  std::vector<uint32_t> flat_pairs() const;
  //! The reference positions, 3 floats a vertex (they hold floats' values).
  std::vector<float> reference_floats() const;
  //! A vertex whose largest move along an axis from its reference, doubled,
  //! exceeds this may have left a pair off the list (update() then looks
  //! again): the gap less update()'s rounding allowance at the largest
  //! extent the positions can have while no vertex does.
  double move_limit() const;

  //! How many times the whole list has been built, and how many times the
  //! pairs of some of its triangles have been looked for again.
  size_t builds() const { return builds_; }
  size_t refreshes() const { return refreshes_; }

 private:
  //! The mesh's triangles at the reference positions, and their tree, made
  //! at the whole list's build and refitted at each refresh (a new tree each
  //! time, sorted anew, cost most of a refresh: docs/PERFORMANCE.md). On the
  //! heap, so that the tree's reference to the triangles survives a move.
  struct ReferenceTree {
    MeshTriangles triangles;
    TriangleTree tree;
    explicit ReferenceTree(MeshTriangles at_reference) : triangles(std::move(at_reference)), tree(triangles) {}
  };

  double gap_;
  //! Null until the first build.
  std::unique_ptr<ReferenceTree> reference_;
  //! Per triangle, the triangles it is listed with (each pair under both).
  //! A vector each, so that a refresh touches only the stale triangles' and
  //! their partners' (one array for all, rebuilt at every refresh, made the
  //! guard three times slower on a 92,674-vertex fit: docs/PERFORMANCE.md).
  std::vector<std::vector<uint32_t>> partners_;
  size_t builds_ = 0, refreshes_ = 0;

  //! update()'s allowance for a few float roundings at the coordinates'
  //! magnitude `extent`.
  double rounding_slack(double extent) const;
  //! Brings the list up to `triangles`' positions: nothing, the pairs of the
  //! triangles round the vertices gone too far, or all of it.
  void update(const MeshTriangles& triangles);
  //! Makes the whole list, every vertex's reference its position now.
  void build(const MeshTriangles& triangles);
  //! Looks again for the pairs of the `stale` triangles (per triangle,
  //! nonzero), whose corners have taken new references.
  void refresh(const std::vector<char>& stale);
  //! Lists the pairs found (a < b; a list per thread) under both triangles.
  void add_pairs(const std::vector<std::vector<std::pair<uint32_t, uint32_t>>>& found);
};

}  // namespace mcquad
