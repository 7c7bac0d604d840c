// Joint actuators of contactsim::Client: actuator_cmd_t on
// <prefix>_ACTUATOR_CMD and the joint commands of a lockstep input
// (docs/actuators.md, "Joint channels"). The server checks every value.
#include <algorithm>

#include "contactsim/client.h"
#include "contactsim/protocol.hpp"

namespace contactsim {
namespace {

struct Column {
  int8_t bit;
  std::vector<double> JointCommand::*values;
  std::vector<double> joint_command_t::*wire;
};

const Column kColumns[] = {
    {joint_command_t::TORQUE, &JointCommand::torque, &joint_command_t::torques},
    {joint_command_t::TARGET_POSITION, &JointCommand::target_position, &joint_command_t::target_positions},
    {joint_command_t::TARGET_VELOCITY, &JointCommand::target_velocity, &joint_command_t::target_velocities},
    {joint_command_t::KP, &JointCommand::kp, &joint_command_t::kp},
    {joint_command_t::KD, &JointCommand::kd, &joint_command_t::kd},
    {joint_command_t::EFFORT_LIMIT, &JointCommand::effort_limit, &joint_command_t::effort_limits},
    {joint_command_t::VELOCITY_LIMIT, &JointCommand::velocity_limit, &joint_command_t::velocity_limits},
};

}  // namespace

// A field of another length than the joints is sent as it is, for the
// server to refuse with its message.
joint_command_t EncodeJointCommand(const JointCommand& c) {
  joint_command_t m{};
  m.model_id = c.model_id;
  m.joint_ids = c.joint_ids;
  m.num_ids = static_cast<int32_t>(c.joint_ids.size());
  size_t n = c.joint_ids.size();
  for (const Column& col : kColumns) {
    if (n == 0) n = (c.*col.values).size();
  }
  m.num_joints = static_cast<int32_t>(n);
  for (const Column& col : kColumns) {
    const std::vector<double>& v = c.*col.values;
    if (!v.empty()) m.fields = static_cast<int8_t>(m.fields | col.bit);
    m.*col.wire = v.empty() ? std::vector<double>(n, 0.0) : v;
    (m.*col.wire).resize(n, 0.0);
  }
  return m;
}

CommandResult Client::SetJointActuators(const JointCommand& command) {
  actuator_cmd_t m{};
  m.op = actuator_cmd_t::SET;
  m.joints = EncodeJointCommand(command);
  return Send(std::move(m));
}

CommandResult Client::ClearJointActuators(const std::vector<int64_t>& joint_ids, int64_t model_id) {
  JointCommand c;
  c.model_id = model_id;
  c.joint_ids = joint_ids;
  actuator_cmd_t m{};
  m.op = actuator_cmd_t::CLEAR;
  m.joints = EncodeJointCommand(c);
  return Send(std::move(m));
}

CommandResult Client::Send(actuator_cmd_t command) {
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return Publish(Channel(protocol::kActuatorCmd), command.request_id, buffer.data(), static_cast<int>(buffer.size()));
}

}  // namespace contactsim
