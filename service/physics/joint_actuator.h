// A joint's actuator: the generalized force (torque on a hinge, force on a
// slider) it applies along the joint coordinate q (joint.h), between the
// two bodies, as a motor at the joint would (docs/actuators.md):
//   u = clamp(torque + kp (q_target - q') + kd (v_target - v'),
//             -effort_limit, effort_limit)
// with q' = q + h v' and v' the coordinate and its rate at the END of the
// step: the PD terms are implicit, so that a stiff kp stays stable at any
// step (MuJoCo's implicit position actuators, PhysX's drives; in impulse
// form the row of a soft constraint, Catto, "Soft Constraints", GDC 2011).
// Collecting the terms in v',
//   u = torque + (h kp + kd) (r - v'),  r = (kp e + kd v_target) / (h kp + kd),
// e = q_target - q: a damper of gain h kp + kd towards the target rate r,
// the rate the drive asks for, which is clamped to +-velocity_limit
// (DriveTarget below). As an impulse lambda = u h on the coordinate's rate,
//   v' + lambda / (h (h kp + kd)) = r + torque / (h kp + kd),
// a velocity row with compliance cfm = 1 / (h (h kp + kd)) and bounds
// |lambda| <= effort_limit h: the clamp is exact, and the effort applied is
// lambda / h. The implicit spring damps: I th'' = -kp th stepped so maps
// (th, th') by a matrix of determinant 1 / (1 + h^2 kp / I), an amplitude
// lost of h^2 kp / (2 I) a step, as a damper c = kp h would (a damping ratio
// w h / 2 more, w^2 = kp / I; docs/actuators.md gives the step a response
// needs).
//   torque control:   kp = kd = 0, torque the command: a fixed generalized
//                     force, clamped, applied with gravity (no row);
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

// True when the PD terms act (kp or kd > 0): the actuator is a drive row of
// the contact method; without them its torque is a fixed force.
inline bool HasDriveGains(const JointActuator& a) { return a.kp > 0.0 || a.kd > 0.0; }

// The effort clamped to +-effort_limit.
double ClampEffort(const JointActuator& a, double effort);

// The position error q_target - q the drive sees: wrapped into (-pi, pi]
// when `wrap` (a hinge without limits), else the plain difference.
double ActuatorPositionError(const JointActuator& a, double q, bool wrap);

// The drive of an actuator with gains over a step h > 0, as the velocity row
// on the coordinate's rate v' derived above: v' + cfm lambda = rate, with
// |lambda| <= max_impulse.
struct DriveTarget {
  double cfm = 0.0;          // 1 / (h (h kp + kd))
  double rate = 0.0;         // clamp(r, +-velocity_limit) + torque / (h kp + kd)
  double max_impulse = 0.0;  // effort_limit h (infinite: no limit)
};
// `error` is ActuatorPositionError.
DriveTarget MakeDriveTarget(const JointActuator& a, double error, double h);

// Finite torque and targets, kp and kd finite and >= 0, limits > 0 (may be
// infinite). The message names the field and the value.
Status CheckJointActuator(const JointActuator& actuator);

}  // namespace contactsim
