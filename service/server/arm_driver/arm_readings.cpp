#include "service/server/arm_driver/arm_readings.h"

#include <cmath>
#include <string>

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

Status CheckArmReadings(double sim_time_s, const ArmJointReadings& in) {
  if (!std::isfinite(sim_time_s) || sim_time_s < 0) {
    return Status::InvalidArgument("sim_time_s must be finite and >= 0, got " + std::to_string(sim_time_s));
  }
  const size_t n = in.position.size();
  if (n == 0) return Status::InvalidArgument("position is empty: the arm has no joints");
  Status st;
  if (!(st = CheckArray(in.position, n, false, "position")).ok() ||
      !(st = CheckArray(in.velocity, n, false, "velocity")).ok() ||
      !(st = CheckArray(in.position_commanded, n, false, "position_commanded")).ok() ||
      !(st = CheckArray(in.velocity_commanded, n, true, "velocity_commanded")).ok() ||
      !(st = CheckArray(in.torque_commanded, n, false, "torque_commanded")).ok() ||
      !(st = CheckArray(in.torque_applied, n, true, "torque_applied")).ok() ||
      !(st = CheckArray(in.torque_external, n, true, "torque_external")).ok()) {
    return st;
  }
  return Status::Ok();
}

std::vector<double> OrZeros(const std::vector<double>& values, size_t n) {
  return values.empty() ? std::vector<double>(n, 0.0) : values;
}

}  // namespace contactsim
