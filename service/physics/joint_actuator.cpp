#include "service/physics/joint_actuator.h"

#include <cmath>

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

}  // namespace contactsim
