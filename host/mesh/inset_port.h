#pragma once

#include <Eigen/Geometry>

#include "mesh/quad_soup.h"

namespace mcquad {

//! A port wider than this many times its limb's radius at the root gets a
//! port of the limb's size inset in it (inset_port). The generated thin
//! branch's port (a fifth of its trunk, at 60 degrees) is 4.3 times as wide
//! as the branch; the armadillo's tail's 3.04 times, the only one of the six
//! scans' limbs over it (docs/HARD_CASES.md, "Thin limbs get ports of their
//! own size").
constexpr double kInsetPortRatio = 3.0;

//! A limb whose bone leaves its port further than this cosine (about 30
//! degrees) off the port's normal gets no inset (limbs_to_inset).
constexpr double kInsetLeastCosine = 0.85;

//! A ring of `radius` inside `port`, centred where the bone leaving `node`
//! along `direction` (unit) crosses the port's plane, joined to the port's
//! ring by 8 quads lying in that plane; returns it as the port the limb's
//! tube attaches to.
//!
//! A block's face is as large as its neighbours let it be: a thin limb off a
//! trunk gets a face as wide as the trunk's, and its tube narrowed from that
//! face to its own radius in one ring, a funnel. At the start fraction the
//! funnel lay inside the trunk and its upper half faced up the trunk's
//! inside, where no ray finds the cloud: the generated thin branch kept a
//! pocket 0.4 r deep above its root (docs/HARD_CASES.md, "Thin limbs get
//! ports of their own size"). The inset's band faces the way the face does,
//! out of the block, and the limb's tube starts at its own radius.
Port inset_port(QuadSoup& soup, const Port& port, const Eigen::Vector3d& node, const Eigen::Vector3d& direction,
                double radius);

}  // namespace mcquad
