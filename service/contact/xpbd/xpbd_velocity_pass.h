// The velocity pass of the xpbd contacts (Mueller et al. 2020, sec. 3.6),
// after each sub-step's velocities are taken from its poses, for every point
// that pushed in the sub-step:
//   * restitution: v_n -> max(-e v~_n, 0), v~_n the normal velocity before
//     the position solve, e = 0 when |v~_n| is below the threshold (so a
//     resting contact does not jitter); a block's pushing points at once
//     through the inverse of their K (K^+ for a face's four), so a face's
//     corners share it whatever their order;
//   * dynamic friction per patch (xpbd_patch_friction.h, BrakeXpbdPatch):
//     the impulse that stops the patch's sliding and twist, at most
//     mu sum lambda_n / h (eq. 30 with f_n = lambda_n / h^2), before the
//     restitution and again after it, the two within that limit together.
//     Where static friction held the patch this removes what its
//     linearisation left; skipping those patches let a box on a slope creep.
// It also adds the sub-step's impulses to the points' report (XpbdPoint::
// impulse): the pushes lambda_n / h along n, and the patch's static and
// dynamic friction shared among the points by their pushes.
#pragma once

#include <vector>

#include "service/contact/normal_block.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/xpbd/xpbd_contact.h"
#include "service/contact/xpbd/xpbd_patch_friction.h"

namespace contactsim {

// The velocity pass on the bodies' v and w; restitution applies above
// `restitution_threshold` (m/s), except in the blocks marked in `deferred`
// (xpbd_restitution.h, after this pass); `patches` and `caches` are parallel
// to `blocks`; `predicted` holds the bodies' v~ and w~ (before the position
// solve); the jointed blocks' impulses go to their bodies' components
// (`articulation`).
void SolveXpbdContactVelocities(double h, double restitution_threshold, const std::vector<NormalBlock>& blocks,
                                const std::vector<char>& deferred, int begin, int end,
                                const std::vector<XpbdPatch>& patches,
                                std::vector<XpbdSubsetCache>& caches, const std::vector<XpbdPose>& predicted,
                                const XpbdArticulation& articulation, std::vector<SoftBody>& bodies,
                                std::vector<XpbdPoint>* points);

}  // namespace contactsim
