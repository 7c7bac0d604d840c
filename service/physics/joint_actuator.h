// A joint's actuator: the generalized force (torque on a hinge, force on a
// slider) it applies along the joint coordinate q (joint.h), between the
// two bodies, as a motor at the joint would (docs/actuators.md):
//   u = clamp(torque + kp (q_target - q') + kd (v_target - v'),
//             -effort_limit, effort_limit)
// with q' = q + h v' and v' the coordinate and its rate at the END of the
// step: the PD terms are implicit, so that a stiff kp stays stable at any
// step (MuJoCo's implicit position actuators, PhysX's drives; in impulse
// form the row of a soft constraint, Catto, "Soft Constraints", GDC 2011).
// The clamp is exact: the impulse the step applies is bounded by
// effort_limit h. The drive's target rate is clamped to velocity_limit.
//   torque control:   kp = kd = 0, torque the command;
//   velocity control: kp = 0, kd > 0, target_velocity;
//   position control: kp > 0 (kd >= 0), target_position (and velocity).
// A hinge without limits (continuous) drives the angle error wrapped into
// (-pi, pi], the short way round; a hinge with limits and a slider use the
// plain difference.
#pragma once

#include <limits>
#include <string>

#include "service/physics/status.h"

namespace contactsim {

struct JointActuator {
  double torque = 0.0;           // N m (hinge) or N (prismatic): feed-forward effort
  double target_position = 0.0;  // rad or m; acts when kp > 0
  double target_velocity = 0.0;  // rad/s or m/s; acts when kd > 0
  double kp = 0.0;               // N m/rad or N/m, >= 0
  double kd = 0.0;               // N m s/rad or N s/m, >= 0
  double effort_limit = std::numeric_limits<double>::infinity();    // N m or N, > 0
  double velocity_limit = std::numeric_limits<double>::infinity();  // rad/s or m/s, > 0
};

// True when the actuator applies anything (a torque or a gain).
inline bool IsActuated(const JointActuator& a) { return a.torque != 0.0 || a.kp > 0.0 || a.kd > 0.0; }

// Finite torque and targets, kp and kd finite and >= 0, limits > 0 (may be
// infinite). The message names the field and the value.
Status CheckJointActuator(const JointActuator& actuator);

}  // namespace contactsim
