#pragma once

#include <Eigen/Geometry>

#include "mesh/quad_soup.h"

namespace mcquad {

//! A port wider than this many times its limb's radius at the root gets a
//! port of the limb's size inset in it (inset_port). The generated thin
//! branches' ports are 2.8 to 2.9 times as wide as a branch of 0.3 of its
//! trunk (45 to 75 degrees) and 4.3 times a fifth; of the six scans' limbs
//! the armadillo's tail (3.0) and one more of its ports (2.7) are over it.
//! At 2 the kitten took an inset too (2.1) and its coverage got worse
//! (docs/HARD_CASES.md, "Thin limbs start at their trunk's wall").
constexpr double kInsetPortRatio = 2.5;

//! A limb whose bone leaves its port further than this cosine (60 degrees)
//! off the port's normal gets no inset (limbs_to_inset). The thin branch at
//! 45 degrees to its trunk leaves its port 43 degrees off: in the port's
//! plane its inset folded into a plug (mean / p95 1.91 / 3.90 -> 4.67 / 38.1
//! % r), lifted to the trunk's wall it meets every bound (0.59 / 1.69; 0.53
//! / 1.84 turned across the bone).
constexpr double kInsetLeastCosine = 0.5;

//! A limb whose inset would stand further than this many port radii out of
//! its port gets none (limbs_to_inset): it runs on inside its trunk, and a
//! straight frustum cannot follow it. Measured: thin branches at 45 to 90
//! degrees 0.3 to 0.75, the armadillo's ports 1.07 and 1.12; branches whose
//! forks moved out along the trunk (20 to 40 degrees) 1.39 to 2.5, and the
//! one of those inset at 1.5 (35 degrees, 0.3) grew a fin at its crotch.
constexpr double kInsetLongestLift = 1.2;

//! The inset ring stands out of its port's plane to this fraction of the way
//! along its limb to where the limb leaves the junction's other tubes (the
//! trunk's wall). The generated thin branch (a fifth of its trunk, at 60
//! degrees, the ring in the face's plane) met every bound of issue 20 from
//! 0.7 to 1.1 (mean / p95 0.74 / 1.71, 0.35 / 1.50, 0.40 / 1.65, 0.43 /
//! 1.67 % r at 0.7, 0.9, 1.0, 1.1; docs/HARD_CASES.md, "Thin limbs start at
//! their trunk's wall").
constexpr double kInsetLift = 0.9;

//! A ring of `radius` inside `port`, centred where the bone leaving `node`
//! along `direction` (unit) crosses the port's plane, joined to the port's
//! ring by 8 quads; returns it as the port the limb's tube attaches to.
//! `lift` moves the ring that far out of the port's plane along its normal
//! (the bone's crossing then taken in the lifted plane) and, where it stays
//! clear of that plane, turns the ring across the bone (its outward the
//! bone's direction): the 8 quads are a band in the plane without it, a
//! frustum with it.
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
                double radius, double lift = 0);

}  // namespace mcquad
