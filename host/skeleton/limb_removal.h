#pragma once

#include <Eigen/Core>
#include <optional>

#include "io/skeleton_io.h"

namespace mcquad {

//! A limb of a skeleton: the chain of nodes from an end node up to, not
//! including, the first node of another degree (a junction). The limb
//! nearest `site` (by its bones, the one to the junction included) is taken
//! out of `skeleton`, the other nodes renumbered in order; returns where its
//! end node was. Nothing is taken (nullopt) when no limb ends at a junction:
//! a lone chain or a loop is a whole component, not a limb.
std::optional<Eigen::Vector3d> remove_limb_nearest(SkeletonData& skeleton, const Eigen::Vector3d& site);

}  // namespace mcquad
