#include "service/server/arm_driver/arm_driver.h"

#include <cmath>

#include "service/server/arm_driver/arm_external_torque.h"

namespace contactsim {
namespace {

// A count that is the arm's joints or, where allowed, 0.
Status CheckCount(size_t given, size_t joints, const char* field) {
  if (given == 0 || given == joints) return Status::Ok();
  return Status::InvalidArgument(std::string(field) + " has " + std::to_string(given) + " entries; the arm has " +
                                 std::to_string(joints) + " joints (send " + std::to_string(joints) + " or 0)");
}

// The inputs the drives act on (ArmInputs), any joint's counting.
int DriveInputs(const World& world, const ArmJoints& arm) {
  int inputs = 0;
  for (JointId id : arm.joints) {
    const JointActuator& a = world.FindJoint(id)->actuator;
    if (a.kp > 0) inputs |= kArmPositionInput;
    if (a.kd > 0 && (a.kp == 0 || a.target_velocity != 0)) inputs |= kArmVelocityInput;
    if (a.torque != 0) inputs |= kArmTorqueInput;
  }
  return inputs;
}

}  // namespace

Status ArmDriver::Find(const World& world, ArmJoints* arm) const {
  return FindArmJoints(world, config_.model, kArmJoints, arm);
}

Status ArmDriver::Hold(World* world) const {
  ArmJoints arm;
  Status st = Find(*world, &arm);
  if (!st.ok()) return st;
  ArmCommand cmd;
  std::vector<double> velocity;
  ReadArmJoints(*world, arm, &cmd.position, &velocity);
  return Apply(cmd, world);
}

Status ArmDriver::Apply(const ArmCommand& cmd, World* world) const {
  ArmJoints arm;
  Status st = Find(*world, &arm);
  if (!st.ok()) return st;
  const size_t n = arm.joints.size();
  if (!(st = CheckCount(cmd.position.size(), n, "joint_position")).ok() ||
      !(st = CheckCount(cmd.velocity.size(), n, "joint_velocity")).ok() ||
      !(st = CheckCount(cmd.torque.size(), n, "joint_torque")).ok()) {
    return st;
  }
  const bool position = !cmd.position.empty();
  const bool velocity = !cmd.velocity.empty();
  // every value is checked before the first joint changes
  std::vector<JointActuator> drives;
  for (size_t i = 0; i < n; ++i) {
    JointActuator a = world->FindJoint(arm.joints[i])->actuator;
    if (position) a.target_position = cmd.position[i];
    a.target_velocity = velocity ? cmd.velocity[i] : 0.0;
    a.kp = position ? config_.kp[i] : 0.0;
    a.kd = position || velocity ? config_.kd[i] : 0.0;
    a.torque = cmd.torque.empty() ? 0.0 : cmd.torque[i];
    a.effort_limit = arm.effort_limit[i];
    a.velocity_limit = arm.velocity_limit[i];
    if (!(st = CheckJointActuator(a)).ok()) return st;
    drives.push_back(a);
  }
  for (size_t i = 0; i < n; ++i) {
    if (!(st = world->SetJointActuator(arm.joints[i], drives[i])).ok()) return st;
  }
  return Status::Ok();
}

void ArmDriver::BeforeStep(World* world) {
  step_wrenches_.assign(world->wrenches().begin(), world->wrenches().end());  // before the compensation's own
  ArmJoints arm;
  if (config_.gravity_compensation && Find(*world, &arm).ok()) CompensateGravity(arm, world);
}

Status ArmDriver::Read(const World& world, const ContactSet& contacts, ContactValueKind kind,
                       ArmJointReadings* out) const {
  ArmJoints arm;
  Status st = Find(world, &arm);
  if (!st.ok()) return st;
  ArmJointReadings r;
  ReadArmJoints(world, arm, &r.position, &r.velocity);
  const std::vector<double> hold =
      config_.gravity_compensation ? GravityHoldTorques(world, arm) : std::vector<double>(arm.joints.size(), 0.0);
  for (size_t i = 0; i < arm.joints.size(); ++i) {
    const Joint& j = *world.FindJoint(arm.joints[i]);
    r.position_commanded.push_back(j.actuator.target_position);
    r.velocity_commanded.push_back(j.actuator.target_velocity);
    r.torque_commanded.push_back(j.actuator.torque);
    r.torque_applied.push_back(j.effort + hold[i]);
  }
  r.torque_external = ArmExternalTorques(world, arm, contacts, kind, step_wrenches_);
  r.inputs = DriveInputs(world, arm);
  *out = std::move(r);
  return Status::Ok();
}

}  // namespace contactsim
