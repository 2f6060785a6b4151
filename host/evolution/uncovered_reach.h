#pragma once

#include <cstddef>

#include "core/point_cloud.h"
#include "core/quad_mesh.h"
#include "evolution/evolution_backend.h"
#include "evolution/evolution_parameters.h"
#include "mesh/mesh_arrays.h"

namespace mcquad {

//! How far from the mesh, in epsilon, a cloud point must lie to pull it:
//! a tenth of the median radius at the automatic epsilon (0.6 r), twice the
//! verdict's coverage bound, so that a chord's sagitta pulls nothing.
constexpr double kReachDistance = 1.0 / 6.0;
//! The longest move a pulled vertex makes in one round, in epsilon.
constexpr double kReachLongestStep = 0.5;
//! Cloud points the reach looks at, at most: on the real scans (200,000
//! points) all of them, a few dozen per vertex of a default mesh; on a
//! larger cloud a stride, which keeps a round within a fraction of an
//! evolution step.
constexpr size_t kReachSampledPoints = 200000;
//! Rounds of pulling at most.
constexpr int kReachRounds = 16;
//! Evolution steps after the pulling, to settle what it moved onto the cloud.
constexpr unsigned kReachSettleIterations = 5;

//! What the reach for the uncovered cloud did (reach_uncovered_cloud).
struct UncoveredReach {
  int rounds = 0;               //!< rounds that moved some vertex
  size_t vertices_moved = 0;    //!< pulled in the first round
  size_t uncovered_before = 0;  //!< sampled cloud points farther than the distance, before
  size_t uncovered_after = 0;   //!< of those (outliers left out), after the pulling and before the settling
  unsigned settle_iterations = 0;
  //! Whether the fit so reached was kept (pipeline/fit.cpp: where its
  //! cloud -> mesh p95 is lower and, on a scan with normals, the area it
  //! turns against them stays within the verdict's bound or grows not at all).
  bool kept = false;
};

//! The cloud the evolution leaves uncovered, pulled to. The evolution moves
//! each vertex by what its rays see along its normal; a part of the cloud
//! that no vertex's rays reach (a web of the mesh across a concave part, an
//! ear with no bone, a crotch a slot stops short of) stays uncovered however
//! long it runs. Here each sampled cloud point farther than `distance` from
//! the mesh, outside it or inside, pulls the corners of its nearest
//! triangle toward itself, weighted by where the nearest point lies on the
//! triangle, unless it has too few neighbours in the cloud to lie on a
//! surface (an outlier); a vertex pulled by at least four points moves by
//! the mean of their pulls, at most `longest_step`. The crossing guard,
//! started from `start`, shortens any move that would make faces cross,
//! fold or turn over. At most `rounds` rounds, fewer once nothing moves.
UncoveredReach pull_toward_uncovered_cloud(QuadMesh& mesh, const MeshArrays& start, const PointCloud& cloud,
                                           double distance, double longest_step, int rounds);

//! Robust mode, after the evolution: pull_toward_uncovered_cloud with
//! kReachDistance, kReachLongestStep and kReachRounds (epsilon from
//! `parameters`), then, where it moved something, kReachSettleIterations
//! more steps on `backend` (loaded with `start`), numbered from
//! `first_iteration`.
UncoveredReach reach_uncovered_cloud(EvolutionBackend& backend, const MeshArrays& start,
                                     const EvolutionParameters& parameters, const PointCloud& cloud, QuadMesh& mesh,
                                     unsigned first_iteration);

}  // namespace mcquad
