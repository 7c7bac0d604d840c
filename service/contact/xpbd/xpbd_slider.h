// The positional part of a prismatic joint in the xpbd method (Mueller,
// Macklin, Chentanez, Jeschke and Kim 2020, "Detailed rigid body simulation
// with extended position based dynamics", SCA, sec. 3.3.2, "Joints with
// positional limits"), after the weld's angular correction
// (xpbd_joints.h): with d = p_A - p_B and a the axis fixed in A,
//   line: B's anchor moves onto A's line by the part of d across the axis,
//     c = |d - (d . a) a| along (d - (d . a) a) / c;
//   limits: the slide s = a . (p_B - p_A) (PrismaticSlide, physics/joint.h)
//     outside [lower, upper] moves back along a by the excess, only when
//     violated: a one-sided correction, plastic (no bounce).
// Each correction is one XPBD update (positional_correction.h).
#pragma once

#include "service/contact/xpbd/xpbd_joints.h"

namespace contactsim {

// Corrects the slider `j` between a and b (the world: a static body at the
// origin) with compliance alpha_tilde; lambda[1] takes the limit's
// multiplier, lambda[2] the line's.
void SolveXpbdSlide(const Joint& j, RigidBody& a, RigidBody& b, double alpha_tilde, XpbdJointLambda& lambda);

}  // namespace contactsim
