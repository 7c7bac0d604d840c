#include "service/server/arm_driver/iiwa_status_builder.h"

#include <cmath>
#include <string>
#include <utility>

namespace contactsim {
namespace {

// The array has `joints` finite entries, or none when it may be empty.
Status CheckArray(const std::vector<double>& values, size_t joints, bool may_be_empty, const char* field) {
  if (values.empty() && may_be_empty) return Status::Ok();
  if (values.size() != joints) {
    return Status::InvalidArgument(std::string(field) + " has " + std::to_string(values.size()) + " entries, the arm " +
                                   std::to_string(joints) + " joints");
  }
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      return Status::InvalidArgument(std::string(field) + "[" + std::to_string(i) + "] is not finite");
    }
  }
  return Status::Ok();
}

}  // namespace

Status BuildIiwaStatus(double sim_time_s, const IiwaJointReadings& in, drake::lcmt_iiwa_status* out) {
  if (!std::isfinite(sim_time_s) || sim_time_s < 0) {
    return Status::InvalidArgument("sim_time_s must be finite and >= 0, got " + std::to_string(sim_time_s));
  }
  const size_t n = in.position.size();
  if (n == 0) return Status::InvalidArgument("position is empty: the arm has no joints");
  Status st;
  if (!(st = CheckArray(in.position, n, false, "position")).ok() ||
      !(st = CheckArray(in.velocity, n, false, "velocity")).ok() ||
      !(st = CheckArray(in.position_commanded, n, false, "position_commanded")).ok() ||
      !(st = CheckArray(in.torque_commanded, n, false, "torque_commanded")).ok() ||
      !(st = CheckArray(in.torque_applied, n, true, "torque_applied")).ok() ||
      !(st = CheckArray(in.torque_external, n, true, "torque_external")).ok()) {
    return st;
  }
  drake::lcmt_iiwa_status m;
  m.utime = std::llround(sim_time_s * 1e6);
  m.num_joints = static_cast<int32_t>(n);
  m.joint_position_measured = in.position;
  m.joint_velocity_estimated = in.velocity;
  m.joint_position_commanded = in.position_commanded;
  m.joint_position_ipo = in.position_commanded;
  m.joint_torque_commanded = in.torque_commanded;
  m.joint_torque_measured = in.torque_applied.empty() ? in.torque_commanded : in.torque_applied;
  m.joint_torque_external = in.torque_external.empty() ? std::vector<double>(n, 0.0) : in.torque_external;
  *out = std::move(m);
  return Status::Ok();
}

}  // namespace contactsim
