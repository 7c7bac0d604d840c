// The velocity pass of the xpbd contacts (Mueller et al. 2020, sec. 3.6),
// after each sub-step's velocities are taken from its poses, for every point
// that pushed in the sub-step:
//   * restitution: v_n -> max(-e v~_n, 0), v~_n the normal velocity before
//     the position solve, e = 0 when |v~_n| is below the threshold (so a
//     resting contact does not jitter), and v~_n kept where the point was
//     parting already, except at an overlap present at the step's start
//     (AllowXpbdStartOverlaps), whose push-out is positional only; a
//     block's pushing points at once through the inverse of their K (K^+
//     for a face's four), so a face's corners share it whatever their order;
//   * dynamic friction per patch (xpbd_patch_friction.h, BrakeXpbdPatch):
//     the impulse that stops the patch's sliding and twist, at most
//     mu sum lambda_n / h (eq. 30 with f_n = lambda_n / h^2), before the
//     restitution and again after it, the two within that limit together.
//     Where static friction held the patch this removes what its
//     linearisation left; skipping those patches let a box on a slope creep.
// One sweep, block by block, is Gauss-Seidel: on a row of touching bodies
// struck at one end it leaves the row's pairs parting (e = 0 rows 0.14 v0
// off the analytic answer). With `velocity_iterations` > 1 the pass sweeps
// again while a sweep changed some block's velocities by more than 1e-5
// m/s (32 sweeps: within 6e-4 v0; a resting pyramid of 210 boxes does not
// settle to that within 32 and takes 10 times the time a step, so one
// sweep is the default).
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

// A block's brakes over the sweeps of a sub-step's velocity pass: what
// BrakeXpbdPatch has spent (t1, t2, twist) and applied (N s on B, world),
// and the normal impulse the pass's restitution added to the pushes.
struct XpbdPassBlock {
  Vec3 spent = Vec3::Zero();
  Vec3 braked = Vec3::Zero();
  double restitution = 0.0;  // N s, summed over the points and sweeps
};

// Which of a sub-step's velocity sweeps this is: the first starts the
// blocks' brakes; with `report` each block adds its sub-step's impulses to
// its points' report (ReportXpbdSubstepImpulses) after its sweep, when the
// pass takes a single sweep.
struct XpbdVelocitySweep {
  bool first = true;
  bool report = true;
};

// One sweep of the velocity pass on the bodies' v and w; restitution applies above
// `restitution_threshold` (m/s), except in the blocks marked in `deferred`
// (xpbd_restitution.h, after this pass); `patches` and `caches` are parallel
// to `blocks`; `predicted` holds the bodies' v~ and w~ (before the position
// solve); the jointed blocks' impulses go to their bodies' components
// (`articulation`).
double SolveXpbdContactVelocities(double h, double restitution_threshold, const std::vector<NormalBlock>& blocks,
                                const std::vector<char>& deferred, int begin, int end, XpbdVelocitySweep sweep,
                                const std::vector<XpbdPatch>& patches,
                                std::vector<XpbdSubsetCache>& caches, const std::vector<XpbdPose>& predicted,
                                const XpbdArticulation& articulation, std::vector<SoftBody>& bodies,
                                std::vector<XpbdPassBlock>* blocks_state, std::vector<XpbdPoint>* points);

// Adds the sub-step's impulses of blocks [begin, end) to their points'
// report (XpbdPoint::impulse), after the pass's last sweep: the pushes
// lambda_n / h along n, and the patch's static friction and its brakes
// shared among the pushing points by their pushes.
void ReportXpbdSubstepImpulses(double h, const std::vector<NormalBlock>& blocks, int begin, int end,
                               const std::vector<XpbdPatch>& patches, const std::vector<XpbdPassBlock>& brakes,
                               std::vector<XpbdPoint>* points);

}  // namespace contactsim
