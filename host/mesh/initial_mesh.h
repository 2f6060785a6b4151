#pragma once

#include <string>
#include <vector>

#include "core/point_cloud.h"
#include "core/point_index.h"
#include "core/quad_mesh.h"
#include "mesh/junction_block.h"
#include "skeleton/acute_junctions.h"
#include "skeleton/bone_assignment.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

enum class EndMode { kAuto, kOpen, kCapped };

//! Where the construction stops (docs/CONSTRUCTION.md): the junction blocks
//! alone, the tubes swept but not refined, or the refined mesh.
enum class ConstructionStage { kBlocks, kExtruded, kRefined };

struct InitialMeshOptions {
  double start_fraction = 0.7;  //!< initial mesh radius as a fraction of the local cloud radius
  //! The junction blocks' radius as a fraction of the local cloud radius (at
  //! least the start fraction). The start fraction instead at a junction with
  //! a limb that ends or narrows within its blend from the block, and on an
  //! unrefined mesh (MeshAssembler::block_fraction, build_initial_mesh).
  double block_fraction = 0.9;
  //! Where the general block's edge vertices go (mesh/junction_block.h):
  //! between two acute bones toward their crotch, where the cloud has one.
  //! Midway on an unrefined mesh, whose blocks stay at the start fraction
  //! too (build_initial_mesh), and in the paper's mode.
  BlockEdges block_edges = BlockEdges::kAcuteToCrotch;
  //! A limb whose port is over kInsetPortRatio times as wide as its root
  //! (a thin branch off a trunk, whose first bone measured the trunk) gets a
  //! port of its own size inset in it and lifted out of it to the trunk's
  //! wall (mesh/inset_port.h; docs/HARD_CASES.md, "Thin limbs start at their
  //! trunk's wall"). Off in the paper's mode and on the unrefined mesh.
  bool limb_ports = true;
  EndMode ends = EndMode::kAuto;  //!< open/capped ends; auto decides from the cloud
  double resolution = 0;          //!< target edge length; 0 = auto (16 vertices around a tube)
  size_t target_vertices = 0;     //!< alternatively, refine until at least this many vertices
  ConstructionStage stage = ConstructionStage::kRefined;
  //! Junctions whose bones fork more acutely move to where the cloud's tubes
  //! part (skeleton/acute_junctions.h); 0 keeps every junction where it is.
  double min_junction_angle = 75.0 * M_PI / 180.0;
  //! The mesh round each junction moves this fraction of the way to the cloud
  //! along rays from the junction's node (mesh/junction_inflation.h); 0 = off.
  double junction_inflation = 0.85;
  //! Refine only once (the default resolution) even where more levels are
  //! asked for; InitialMesh::finer_levels says how many are left, for the
  //! fit to add after evolving this mesh (coarse to fine, docs/DESIGN.md).
  bool coarse_first = false;
};

struct InitialMesh {
  QuadMesh mesh;
  int open_ends = 0;
  int inset_ports = 0;                  //!< limbs given a port of their own size (InitialMeshOptions::limb_ports)
  int refinement_levels = 0;            //!< Catmull-Clark levels this mesh has
  int finer_levels = 0;                 //!< with coarse_first: levels asked for beyond refinement_levels
  std::vector<bool> irregular_allowed;  //!< per vertex: on a junction block or a cap
  TubeSkeleton skeleton;                //!< the skeleton the mesh was built on (acute junctions moved)
};

//! Builds the paper's rough quad mesh (Fig. 1) automatically: a block at
//! every junction with one quad facing each bone (a rotated cube where the
//! bones fit one, else junction_layout.h's polyhedron; where that leaves
//! faces crossing, the cube wherever possible if that crosses less); chains swept ring by ring (8 vertices a ring) with
//! rotation-minimizing frames; chains between two ports and pure loops closed
//! with the cyclic offset of least twist, the rest spread along the chain;
//! ends capped by a face group or left open; then Catmull-Clark refinement.
//! Errors name the skeleton node (`source` prefixes messages).
//! `cloud_index` (over cloud.points) is built here when not given.
InitialMesh build_initial_mesh(const SkeletonGraph& graph, const BoneAssignment& bones, const PointCloud& cloud,
                               const InitialMeshOptions& options, const std::string& source,
                               const PointIndex<float>* cloud_index = nullptr);

//! Coarse to fine: a mesh already evolved at the default resolution refined
//! `levels` more times, each level's folds and crossings relaxed as the
//! initial mesh's are, then its poor quads (mesh/quad_relaxation.h). The
//! refined mesh has the topology the initial mesh would have had at that
//! resolution, and starts on the cloud instead of inside it.
void refine_fitted_mesh(QuadMesh& mesh, int levels);

}  // namespace mcquad
