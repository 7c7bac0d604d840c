#include "service/server/arm_driver/panda_status_builder.h"

#include <cmath>
#include <utility>

namespace contactsim {
namespace {

int8_t PandaControlMode(int inputs) {
  int mode = 0;
  if (inputs & kArmPositionInput) mode |= drake::lcmt_panda_status::CONTROL_MODE_POSITION;
  if (inputs & kArmVelocityInput) mode |= drake::lcmt_panda_status::CONTROL_MODE_VELOCITY;
  if (inputs & kArmTorqueInput) mode |= drake::lcmt_panda_status::CONTROL_MODE_TORQUE;
  return static_cast<int8_t>(mode);
}

}  // namespace

Status BuildPandaStatus(double sim_time_s, const ArmJointReadings& in, drake::lcmt_panda_status* out) {
  const Status st = CheckArmReadings(sim_time_s, in);
  if (!st.ok()) return st;
  const size_t n = in.position.size();
  drake::lcmt_panda_status m;
  m.utime = std::llround(sim_time_s * 1e6);
  m.num_joints = static_cast<int32_t>(n);
  m.joint_position = in.position;
  m.joint_position_desired = in.position_commanded;
  m.joint_velocity = in.velocity;
  m.joint_velocity_desired = OrZeros(in.velocity_commanded, n);
  m.joint_acceleration_desired.assign(n, 0.0);
  m.joint_torque = in.torque_applied.empty() ? in.torque_commanded : in.torque_applied;
  m.joint_torque_desired = in.torque_commanded;
  m.joint_torque_external = OrZeros(in.torque_external, n);
  m.control_command_success_rate = 1.0;
  // unary +: the generated constants are declared, not defined, so are read by value
  using S = drake::lcmt_panda_status;
  m.robot_mode = static_cast<int8_t>(in.inputs != 0 ? +S::kMove : +S::kIdle);
  m.robot_utime = m.utime;
  m.control_mode = PandaControlMode(in.inputs);
  *out = std::move(m);
  return Status::Ok();
}

}  // namespace contactsim
