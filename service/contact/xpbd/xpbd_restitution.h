// Restitution of the xpbd velocity pass (xpbd_velocity_pass.h) in contact
// components with restitution: instead of each point's own v_n+ = -e v~_n
// (Mueller et al. 2020, eq. 34), which holds a row of touching bodies
// together after a strike, the points that pushed in the sub-step leave
// with the normal velocities of the impacts taken one at a time from the
// predicted velocities v~ (sequential_impacts.h): a Newton's cradle passes
// its strike down the row. The positional push lambda_n moved the bodies
// as the velocity impulse lambda_n / h does, which the rows start from.
#pragma once

#include <vector>

#include "service/contact/normal_block.h"
#include "service/contact/sequential_impacts.h"
#include "service/contact/xpbd/xpbd_contact.h"

namespace contactsim {

// The sub-step's rows, before the velocity pass: marks in `deferred` the
// blocks whose restitution waits for SolveXpbdImpacts (the velocity pass
// leaves their normals alone) and returns whether there are any.
bool GatherXpbdImpacts(double h, double threshold, const std::vector<NormalBlock>& blocks,
                       const std::vector<XpbdPoint>& points, const std::vector<XpbdPose>& predicted,
                       const std::vector<SoftBody>& bodies, SequentialImpacts* impacts, std::vector<char>* deferred);

// After the velocity pass: drives the rows to their targets and adds the
// impulses to the points' report.
void SolveXpbdImpacts(double h, SequentialImpacts* impacts, std::vector<SoftBody>& bodies,
                      std::vector<XpbdPoint>* points);

}  // namespace contactsim
