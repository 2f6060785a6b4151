#pragma once

#include <vector>

#include "skeleton/bone_assignment.h"
#include "skeleton/skeleton_graph.h"

namespace mcquad {

//! A skeleton prepared for building the mesh, with a radius per bone and node.
struct TubeSkeleton {
  SkeletonGraph graph;
  std::vector<double> bone_radius;
  std::vector<double> node_radius;
};

//! Moves junctions whose bones fork at an acute angle (below `min_angle`,
//! radians) up to where the cloud's tubes part. Two tubes of radius r on bones
//! at angle t overlap until about r / sin(t/2) along their bisector, so the
//! cloud's crotch is there and not at the skeleton's junction node: the two
//! bones are rejoined at a new junction just below that crotch, fed by a bone
//! from the old junction. The angle at the new junction is wide enough for a
//! block's faces. Pairs whose bones are too short to move along are kept.
//! Other limbs that part together with the pair, or whose tubes still
//! overlap the pair's past the new junction, move with it as one fan.
TubeSkeleton spread_acute_junctions(const SkeletonGraph& graph, const BoneAssignment& bones, double min_angle,
                                    const std::string& source);

//! The radius of a limb where it leaves its junction, from its chain's bone
//! radii (the junction's bone first): the first bone's, unless that bone is
//! far thicker than the rest of the chain (kFatFirstBone times the median).
//! Then the junction sits inside a fatter tube and the first bone took that
//! tube's points as its own (issue 14's blob-limbs: legs of radius 0.45
//! whose first bones measured 2.4; the generated thin branch's first bone
//! measures 0.96 of its trunk's radius, the rest 0.2): the limb's own radius
//! is its chain's median.
double limb_radius(std::vector<double> chain_radii);

//! Node radii from bone radii: the mean of a node's bones, the smallest of
//! them at a junction.
std::vector<double> node_radii(const SkeletonGraph& graph, const std::vector<double>& bone_radius);

}  // namespace mcquad
