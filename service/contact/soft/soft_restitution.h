// The soft step's restitution after its sub-steps (soft_method.h, step 3):
// the points that pushed in the step, in components where one met faster
// than the threshold, are driven to the normal velocities the impacts taken
// one at a time give (sequential_impacts.h), which for a lone pair is Box2D
// v3's v_n = -e v_impact (Catto, Solver2D "Soft Step", 2024) and carries a
// strike down a row of touching bodies as a Newton's cradle does.
//
// The velocities before the solve are the bodies' at the step's start (the
// world's P and L, which the sub-steps leave until they are stored), and a
// point that was apart at the step's start adds what its approach gained
// over its gap (SoftPoint::impact_speed, free flight).
//
// Components without restitution take part where a point that pushed met
// faster than the threshold or leaves the sub-steps parting faster than it
// (SequentialImpacts' `struck`; a point with friction only where no static
// body holds its component; docs/physics.md, "Restitution across
// simultaneous contacts"): their rows then leave with e = 0's
// one-at-a-time answer, every pair of a struck row at one speed, where one
// relax pass a sub-step left them parting by up to 0.097 v0. The stage
// takes the friction of the points without restitution (their step
// totals gain its friction impulses); with restitution it stays normal
// only, as its friction moved the restitution scenes' trajectories. The parting
// is the springs' push-out of the overlap an impact left, which the relax
// pass did not take back in the steps after it; a resting pyramid's points
// part at most 0.13 of the threshold (0.0102 m/s against 2 |g| dt), and a
// tenth of the threshold ran the stage over the whole pyramid in a step of
// 60 and cost 8.8% more instructions.
//
// A step at rest runs none of it: when no point that pushed met faster than
// the threshold and every such point leaves the sub-steps with |v_n| within
// kRestShare of the threshold (what the impacts' own solve counts as rest,
// sequential_impacts.cpp; without restitution, parting no faster than the
// threshold), the targets would all be about 0 and the solve
// would only stir a face's four dependent corners until its passes change
// the velocities by less than that share: a hull resting with e = 0.5 was
// left rocking at 2.7e-5 and 4.2e-5 m/s in a period-two cycle of the steps,
// and at 1e-14 m/s without it.
#pragma once

#include <vector>

#include "service/contact/sequential_impacts.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/soft/soft_manifold.h"

namespace contactsim {

// Whether a point without restitution that pushed calls for the stage
// (above): it met faster than `threshold` or leaves parting faster than it.
bool SoftPointStruck(double threshold, const SoftPoint& p, const std::vector<SoftBody>& bodies);

// Whether the step's points need the restitution stage at all (above):
// some point that pushed met faster than `threshold` or leaves moving along
// its normal faster than kRestShare of it (without restitution: parting
// faster than it). From the points' anchors, not their rows, which the
// float path's points come without (soft_contact.h).
bool SoftStepNeedsRestitution(double threshold, const std::vector<SoftPoint>& points,
                              const std::vector<SoftBody>& bodies);

// The restitution of the step's points (serial: the impacts pass a strike
// from pair to pair in order). Adds the impulses to each point's lambda_n
// and total_n.
void RestituteSoftPoints(double threshold, const World& world, const std::vector<SoftManifold>& manifolds,
                         std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies, SequentialImpacts* impacts);

}  // namespace contactsim
