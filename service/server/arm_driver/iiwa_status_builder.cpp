#include "service/server/arm_driver/iiwa_status_builder.h"

#include <cmath>
#include <utility>

namespace contactsim {

Status BuildIiwaStatus(double sim_time_s, const ArmJointReadings& in, drake::lcmt_iiwa_status* out) {
  const Status st = CheckArmReadings(sim_time_s, in);
  if (!st.ok()) return st;
  const size_t n = in.position.size();
  drake::lcmt_iiwa_status m;
  m.utime = std::llround(sim_time_s * 1e6);
  m.num_joints = static_cast<int32_t>(n);
  m.joint_position_measured = in.position;
  m.joint_velocity_estimated = in.velocity;
  m.joint_position_commanded = in.position_commanded;
  m.joint_position_ipo = in.position_commanded;
  m.joint_torque_commanded = in.torque_commanded;
  m.joint_torque_measured = in.torque_applied.empty() ? in.torque_commanded : in.torque_applied;
  m.joint_torque_external = OrZeros(in.torque_external, n);
  *out = std::move(m);
  return Status::Ok();
}

}  // namespace contactsim
