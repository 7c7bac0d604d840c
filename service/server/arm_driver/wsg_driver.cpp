#include "service/server/arm_driver/wsg_driver.h"

#include <algorithm>
#include <cmath>

#include "service/physics/validation.h"

namespace contactsim {
namespace {

std::string Millimetres(double m) { return FormatValue(m * 1e3); }

}  // namespace

Status WsgDriver::Find(const World& world, WsgFingers* fingers) const {
  return FindWsgFingers(world, config_.model, config_.finger_joints, fingers);
}

Status WsgDriver::SetDrives(const WsgFingers& f, const double (&q)[2], double force, World* world) const {
  JointActuator drives[2];
  for (int i = 0; i < 2; ++i) {
    JointActuator a;
    a.target_position = q[i];
    a.kp = config_.kp;
    a.kd = config_.kd;
    a.effort_limit = std::min(force, f.effort_limit[i]);
    // no velocity limit: the drive clamps the rate it asks for
    // (joint_actuator.h), which at a stall would cap the grip force at
    // (h kp + kd) velocity_limit instead of `force` (wsg_driver.h)
    const Status st = CheckJointActuator(a);
    if (!st.ok()) return st;
    drives[i] = a;
  }
  for (int i = 0; i < 2; ++i) {
    const Status st = world->SetJointActuator(f.joints[i], drives[i]);
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

Status WsgDriver::Hold(World* world) const {
  WsgFingers f;
  Status st = Find(*world, &f);
  if (!st.ok()) return st;
  double q[2], v[2];
  ReadWsgFingers(*world, f, q, v);
  return SetDrives(f, q, kDefaultWsgForce, world);
}

Status WsgDriver::Apply(const WsgCommand& cmd, World* world) const {
  WsgFingers f;
  Status st = Find(*world, &f);
  if (!st.ok()) return st;
  const double d = cmd.target_position_mm * 1e-3;
  if (d < f.min_separation || d > f.max_separation) {
    return Status::InvalidArgument("target_position_mm " + FormatValue(cmd.target_position_mm) +
                                   " is outside the fingers' range [" + Millimetres(f.min_separation) + ", " +
                                   Millimetres(f.max_separation) + "] mm");
  }
  const double q[2] = {f.sign[0] * d / 2, f.sign[1] * d / 2};
  return SetDrives(f, q, cmd.force, world);
}

Status WsgDriver::Read(const World& world, WsgReading* out) const {
  WsgFingers f;
  const Status st = Find(world, &f);
  if (!st.ok()) return st;
  WsgReading r;
  ReadWsgSeparation(world, f, &r.separation, &r.speed);
  // an effort towards closing is -s u on a finger opening to s
  double closing = 0;
  for (int i = 0; i < 2; ++i) closing -= f.sign[i] * world.FindJoint(f.joints[i])->effort;
  r.force = std::abs(closing / 2);
  *out = r;
  return Status::Ok();
}

}  // namespace contactsim
