#pragma once

#include <cmath>
#include <cstdint>

namespace mcquad {

//! Parameters of the Monte Carlo evolution, with the paper's defaults.
//! Lengths left at 0 are derived from the cloud's local radius (see
//! automatic_epsilon in pipeline/prepare.h), so the defaults work at any scale.
struct EvolutionParameters {
  unsigned cones = 4;              //!< c
  unsigned generators = 6;         //!< r: rays per cone
  double alpha_max = M_PI / 18.0;  //!< maximal cone half angle, radians
  unsigned samples = 10;           //!< m: random points per hit cell
  double epsilon = 0.0;            //!< feasibility bound; 0 = auto (0.6 x median radius, automatic_epsilon)
  unsigned iterations = 20;        //!< iteration cap
  double tolerance = 0.0;          //!< stop when the error level improves by less (relative); 0 = never
  uint32_t seed = 1;
  //! kRobust (default) adds the improvements over the paper (docs/DESIGN.md);
  //! kPaper is the paper's step exactly.
  enum class Mode { kPaper, kRobust } mode = Mode::kRobust;
  //! Robust mode: weight of a tangential relaxation before each step (0 =
  //! off; docs/DESIGN.md has its mixed effect).
  double relaxation = 0.0;
  //! Robust mode: a cell's distance along a ray is the mean of its samples'
  //! projections instead of their minimum (docs/DESIGN.md).
  bool mean_projection = true;
  //! Robust mode: vertices in holes of the scan take their neighbours' offset.
  bool fill_holes = true;
  //! Robust mode: a vertex whose rays find no feasible cell while the cloud
  //! is within epsilon of it (a slit in a crease, not a hole) moves along
  //! the scan's normal at its nearest point to that point's level
  //! (mcq_nearest_plane_position). Off by default: closer fits everywhere,
  //! but more faces turned on some shapes and scans (docs/DESIGN.md,
  //! "Blind vertices").
  bool nearest_plane = false;
  //! Robust mode: moves that make faces cross are undone after each step
  //! (mesh/crossing_guard.h).
  bool crossing_guard = true;
  //! With the guard, a backend that can test a step for it does (the
  //! positions then stay on the device unless the guard has something to
  //! hold back); the same positions either way. Off: the host tests every
  //! step (for tests and measurements).
  bool guard_test_on_backend = true;
  //! Robust mode, with the guard: weight of the tangential relaxation of the
  //! vertices it held back, after each step (0 = none).
  double held_back_relaxation = 0.6;
  //! Robust mode: a vertex sees only the cells of the bones near its own
  //! (cells/skeleton_regions.h).
  bool own_cells = true;
  //! Robust mode, finer than the default resolution: the fit evolves the
  //! default resolution's mesh first, refines it and evolves again
  //! (pipeline/fit.cpp, docs/DESIGN.md).
  bool coarse_to_fine = true;
  //! Robust mode, at the default resolution (neither a resolution nor a
  //! vertex target asked for): where the fitted mesh leaves the cloud
  //! uncovered by the verdict's bound, it is refined once and evolved again,
  //! coarse to fine (pipeline/fit.cpp, docs/DESIGN.md).
  bool refine_uncovered = true;
  //! Robust mode: epsilon and the ray reach scale with the vertex's bone
  //! radius over the median radius (docs/DESIGN.md).
  bool local_epsilon = true;
  //! Robust mode: a ray's distance is the mean over every cell its line
  //! crosses within this fraction of epsilon of its first hit, instead of
  //! the first cell's alone (0 = the first cell, the paper's; docs/DESIGN.md).
  double hit_band = 0.4;
  //! Robust mode, on a scan with normals: rays pass through cells whose
  //! scan normals face away from the vertex's normal (the far wall of a
  //! thin part, the other side of a crease), cells/cell_facing.h.
  bool facing_cells = true;
  //! The least cosine of the angle between a cell's scan normal and the
  //! vertex normal for a ray to hit the cell, in [-1, 0.95] (cells with no
  //! normals, or normals that disagree, stay visible).
  double min_facing = 0.7;
  //! Robust mode: each sample's projection onto a ray is corrected by the
  //! mesh's shape operator at the vertex (mcq_vertex_shape_operator), so that
  //! vertices settle on a curved surface rather than inside it by the cells'
  //! sagitta (docs/DESIGN.md, "Curvature correction").
  bool curvature_correction = true;
  //! With the curvature correction: the shape operator of the mesh the
  //! evolution started from, not of the current one. The fit sets it for
  //! the evolution of a fitted mesh refined (coarse to fine): there the
  //! current mesh's curvature, fitted over edges shorter than the samples'
  //! spread, feeds its own noise back (docs/DESIGN.md).
  bool curvature_at_start = false;
  //! Robust mode, on a scan with normals: after the evolution, at most this
  //! many rounds of smoothing the faces turned against the scan's normals
  //! (evolution/turned_face_smoothing.h); 0 = off.
  unsigned turned_face_rounds = 20;
  //! Robust mode, on a scan with normals, with the smoothing of turned faces:
  //! vertices left deep below the scan are pushed out first, and the fit so
  //! pushed is kept where it turns no more of its area against the scan
  //! (evolution/deep_vertex_push.h, turned_face_smoothing.h).
  bool push_deep = true;
  //! Robust mode: after the evolution, the cloud it left uncovered pulls
  //! the mesh (evolution/uncovered_reach.h); the fit so reached is kept
  //! where its cloud -> mesh p95 is lower and, on a scan with normals, the
  //! area it turns against them stays within the verdict's bound or grows
  //! not at all (pipeline/fit.cpp).
  bool reach_uncovered = true;
};

}  // namespace mcquad
