// Restitution of the xpbd velocity pass (xpbd_velocity_pass.h) in contact
// components with restitution: instead of each point's own v_n+ = -e v~_n
// (Mueller et al. 2020, eq. 34), which holds a row of touching bodies
// together after a strike, the points that pushed in the sub-step leave
// with the normal velocities of the impacts taken one at a time from the
// predicted velocities v~ (sequential_impacts.h): a Newton's cradle passes
// its strike down the row. The positional push lambda_n moved the bodies
// as the velocity impulse lambda_n / h does, which the rows start from.
//
// Components without restitution take part too where a point approached
// or parted faster than `strike` at the step's start (a point with
// friction only where no static body holds its component, and then with
// the stage's friction, which holds the slip the velocity pass left so as
// not to undo it; docs/physics.md, "Restitution across simultaneous
// contacts"): their rows leave with e = 0's one-at-a-time answer, every
// pair of a struck row at one speed, where the velocity pass's one sweep a
// sub-step left them parting by up to 0.144 v0.
// A struck body keeps its component in the stage for the rest of the step,
// while the sub-steps pass the impact's overlap down the row and push it
// out. `strike` is max(threshold, 2 |g| dt), a step's gravity, not a
// sub-step's: a resting stack's sweeps leave its points approaching faster
// than 2 |g| h at a sub-step's start (the 20-row pyramid up to 3.2 times,
// with 10 sub-steps), and a stage over the whole stack in those sub-steps
// cost its step 25 times the instructions. The strikes are looked for once
// a step, before the sub-steps: a look every sub-step cost the pyramid 2.8%;
// parting at the step's start counts, as the steps after an impact still
// push its overlap out.
#pragma once

#include <vector>

#include "service/contact/normal_block.h"
#include "service/contact/sequential_impacts.h"
#include "service/contact/xpbd/xpbd_contact.h"

namespace contactsim {

// Before the sub-steps: marks in `struck` (per body) the dynamic bodies of
// the points approaching or parting faster than `strike` (with friction and
// without restitution: in a component of the step's points that no static
// or kinematic body holds)
// (m/s; `frames` parallel to `points`) and returns whether the step needs
// the stage at all (a strike, or a point with restitution).
bool MarkXpbdStrikes(double strike, const std::vector<XpbdPoint>& points, const std::vector<XpbdPointFrame>& frames,
                     const std::vector<SoftBody>& bodies, std::vector<char>* struck);

// The sub-step's rows, before the velocity pass: marks in `deferred` the
// blocks whose restitution waits for SolveXpbdImpacts (the velocity pass
// leaves their normals alone) and returns whether there are any; adds the
// bodies of the rows that take part to `struck`.
bool GatherXpbdImpacts(double h, double threshold, const std::vector<NormalBlock>& blocks,
                       const std::vector<XpbdPoint>& points, const std::vector<XpbdPointFrame>& frames,
                       const std::vector<XpbdPose>& predicted, const std::vector<SoftBody>& bodies,
                       SequentialImpacts* impacts, std::vector<char>* deferred, std::vector<char>* struck);

// After the velocity pass: drives the rows to their targets and adds the
// impulses to the points' report.
void SolveXpbdImpacts(double h, SequentialImpacts* impacts, std::vector<SoftBody>& bodies,
                      std::vector<XpbdPoint>* points);

}  // namespace contactsim
