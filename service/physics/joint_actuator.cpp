#include "service/physics/joint_actuator.h"

#include <algorithm>
#include <cmath>

#include "service/physics/math.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

Status CheckGain(const char* field, double v) {
  if (!std::isfinite(v) || v < 0.0) {
    return Status::InvalidArgument(std::string(field) + " must be finite and >= 0, got " + std::to_string(v));
  }
  return Status::Ok();
}

Status CheckLimit(const char* field, double v) {
  if (std::isnan(v) || v <= 0.0) {
    return Status::InvalidArgument(std::string(field) + " must be > 0 (infinite: no limit), got " +
                                   std::to_string(v));
  }
  return Status::Ok();
}

}  // namespace

Status CheckJointActuator(const JointActuator& a) {
  for (const Status& st :
       {CheckFinite("torque", a.torque), CheckFinite("target_position", a.target_position),
        CheckFinite("target_velocity", a.target_velocity), CheckGain("kp", a.kp), CheckGain("kd", a.kd),
        CheckLimit("effort_limit", a.effort_limit), CheckLimit("velocity_limit", a.velocity_limit)}) {
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

double ClampEffort(const JointActuator& a, double effort) {
  return std::clamp(effort, -a.effort_limit, a.effort_limit);
}

double ActuatorPositionError(const JointActuator& a, double q, bool wrap) {
  const double e = a.target_position - q;
  if (!wrap) return e;
  // into (-pi, pi]: the short way round a continuous hinge
  const double w = std::remainder(e, 2.0 * kPi);
  return w <= -kPi ? w + 2.0 * kPi : w;
}

DriveTarget MakeDriveTarget(const JointActuator& a, double error, double h) {
  const double gain = h * a.kp + a.kd;  // N m s/rad or N s/m: the damper the drive is over a step
  DriveTarget d;
  d.cfm = 1.0 / (h * gain);
  const double r = (a.kp * error + a.kd * a.target_velocity) / gain;
  d.rate = std::clamp(r, -a.velocity_limit, a.velocity_limit) + a.torque / gain;
  d.max_impulse = a.effort_limit * h;
  return d;
}

}  // namespace contactsim
