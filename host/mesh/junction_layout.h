#pragma once

#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace mcquad {

//! The most bones one junction may have. The layout search below is bounded
//! (the best choice found within its bound is kept); measured here, one
//! junction takes 2 ms (skew 3) to 0.37 s (skew 10 and 12), 0.09 s at skew
//! 16 and 0.67 s for a planar 8 at uneven angles.
constexpr int kMaxJunctionValence = 16;

//! UnsupportedError when a junction of `valence` bones exceeds that.
void check_junction_valence(size_t valence);

//! The combinatorics of a junction block, on the unit sphere of directions
//! around the junction node. The block is a closed all-quad polyhedron with
//! exactly one quad face per bone (the face that faces it); one Catmull-Clark
//! split turns each of those quads into the 8-vertex ring a tube attaches to.
//! Its corners sit between the bones, its edges separate neighbouring bones.
struct JunctionLayout {
  std::vector<Eigen::Vector3d> corner_directions;  //!< unit directions of the polyhedron's vertices
  std::vector<std::array<int, 2>> edges;           //!< polyhedron edges (corner ids)
  //! Per bone: its quad, as 4 corners counter-clockwise seen from outside,
  //! and the edge between corner k and corner k+1.
  std::vector<std::array<int, 4>> bone_corners;
  std::vector<std::array<int, 4>> bone_edges;
  //! Closed faces where the bones leave a wide gap: a polygon each, with its
  //! centre's direction, corners counter-clockwise seen from outside and the
  //! edge after each corner.
  std::vector<Eigen::Vector3d> filler_directions;
  std::vector<std::vector<int>> filler_corners, filler_edges;
  int irregular_vertices = 0;  //!< once split, with tubes attached
  //! The most quads round one of its vertices once split, with the tubes
  //! attached: a corner's, or a filler's centre's.
  int highest_valence = 0;
  double score = 0;  //!< the search's cost: lower faces the bones better
};

//! Lays out the block for bones leaving the node in `directions` (unit) with
//! tube `radii`. Valence 3..kMaxJunctionValence, any directions at least 1
//! degree apart (coplanar, all in one hemisphere, uneven angles).
//!
//! How: the dual of a 4-regular graph on the sphere is an all-quad
//! polyhedron with one face per graph vertex. The graph is drawn from the
//! bones' spherical Delaunay triangulation (their convex hull): every bone
//! keeps 4 of its Delaunay edges, an edge may be doubled (its two copies
//! enclose a two-sided face, whose dual corner is a regular vertex of the
//! block), and a dropped edge merges its two triangles into one face. Of all
//! such choices an exhaustive search keeps the one whose quads face their
//! bones best: corners evenly spread around each bone, at even angles from it,
//! and few vertices of other than 4 quads, the fewer the further from 4.
//! Where that leaves a vertex of more than 8 quads, fillers in narrower gaps
//! may part it (junction_layout.cpp, kNarrowGap).
//! UnsupportedError when no choice exists (not seen on any tested shape).
JunctionLayout layout_junction(const std::vector<Eigen::Vector3d>& directions, const std::vector<double>& radii);

}  // namespace mcquad
