// The joint torques that forces from outside the arm apply to it in a step:
// contacts and the external wrenches (APPLY_FORCE, lockstep inputs), not
// gravity, the drives or the gravity compensation. What Drake's iiwa status
// reports as joint_torque_external (iiwa_status_builder.h).
//
// A real iiwa estimates it as its joint torque sensors' reading minus its
// dynamic model's torque; the simulation knows the forces, so it sums them
// directly: the generalized force of the external wrenches (Craig,
// "Introduction to Robotics", sec. 5.9, "Static forces in manipulators",
// tau = J^T F) on each joint's outboard bodies,
//   tau_i = a_i . sum_b ((x_b - p_i) x F_b + T_b),
// with a_i the joint's axis and p_i its anchor in the world, F_b the force
// on body b (at its centre of mass) and T_b the torque on it. A positive
// tau_i turns joint i towards larger angles, as the hold torques of
// GravityHoldTorques do (arm_joints.h); a drive that holds the arm against
// it applies -tau_i.
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"
#include "service/server/arm_driver/arm_joints.h"

namespace contactsim {

// N m per arm joint: the step's `contacts` (values of `kind`: impulses are
// divided by world.dt, contact_wrench.h) and `wrenches`, those of the world
// when the step began (before the driver added its gravity compensation),
// at the arm's poses now.
std::vector<double> ArmExternalTorques(const World& world, const ArmJoints& arm, const ContactSet& contacts,
                                       ContactValueKind kind, const std::vector<TimedWrench>& wrenches);

}  // namespace contactsim
