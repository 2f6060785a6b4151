#pragma once

#include <string>

#include "cells/cell_tree.h"
#include "cells/skeleton_regions.h"
#include "core/point_cloud.h"
#include "core/point_index.h"
#include "mesh/initial_mesh.h"
#include "mesh/mesh_arrays.h"
#include "pipeline/stage_timer.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! Median of the bones' radii: the scale the automatic parameters follow.
double median_bone_radius(const BoneAssignment& bones);

//! The automatic epsilon (and ray reach) for a cloud of this median radius:
//! far enough to see the surface from the initial mesh at 0.7 r, well short
//! of the opposite wall (docs/DESIGN.md).
double automatic_epsilon(double median_radius);

//! Points per cell: `requested`, or with 0 the automatic size: 6 points up
//! to two million points, then in proportion to the cloud, so that cells
//! keep the physical size they have at two million points. Six points buy
//! accuracy on clouds like the paper's (docs/DESIGN.md); on denser clouds
//! the cells are smaller than the mesh can resolve anyway, and the cell
//! arrays would outgrow the cloud itself (docs/PERFORMANCE.md).
size_t cell_leaf_size(size_t requested, size_t points);

//! How far prepare_evolution goes: the initial mesh alone (mcquad init),
//! with the cells too (measuring a mesh), or everything the evolution needs.
//! The most points the radii and the initial mesh read: larger clouds give
//! them an even sample of this size (the cells and the evolution still use
//! every point).
constexpr size_t kMaxSetupPoints = 4000000;

enum class SetupScope { kInitialMesh, kCells, kEvolution };

//! Everything the evolution starts from, built from a cloud and its
//! skeleton graph: radii, the initial mesh, the cells and the flat arrays.
//! Members past the scope asked for stay empty.
struct EvolutionSetup {
  BoneAssignment bones;  //!< the radii only (per-point assignments released)
  double median_radius = 0;
  InitialMesh initial;
  CellTree cells;
  MeshArrays arrays;
  SkeletonRegions regions;
};

//! The one stage sequence from a skeleton graph to the evolution's inputs,
//! each stage run under `timer`: point_index, radius, initial_mesh, cells,
//! cell_facing, regions. The fit, `mcquad metrics`, the tests and the benchmarks all
//! call it. The point index is freed before the cells are built, so the
//! two trees over the cloud never coexist (docs/PERFORMANCE.md, memory).
//! `leaf_size` as in cell_leaf_size (0: automatic). The cells face the way
//! the scan's normals say (orient_cells): those of `scan_normals`, or when
//! it is null the cloud's own (cloud.oriented, else cloud.normals).
EvolutionSetup prepare_evolution(const SkeletonGraph& graph, const PointCloud& cloud, const InitialMeshOptions& options,
                                 size_t leaf_size, const std::string& source, SetupScope scope = SetupScope::kEvolution,
                                 StageTimer* timer = nullptr, const OrientedSample* scan_normals = nullptr);

}  // namespace mcquad
