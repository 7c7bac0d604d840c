// Joint half of contactsim::Client: typed calls to joint_cmd_t on
// <prefix>_JOINT_CMD. As for bodies, the server is the one gate for bad
// input; nothing is checked here.
#include <algorithm>

#include "contactsim/client.h"

#include "contactsim/protocol.hpp"

namespace contactsim {

Result<int64_t> Client::AddJoint(JointType type, int64_t body_a, int64_t body_b,
                                 const Eigen::Vector3d& anchor,
                                 const JointOptions& options) {
  joint_cmd_t command{};  // lcm-gen types leave numbers uninitialised
  command.op = joint_cmd_t::ADD;
  command.kind = static_cast<int8_t>(type);
  command.body_a = body_a;
  command.body_b = body_b;
  std::copy(anchor.data(), anchor.data() + 3, command.anchor);
  command.has_axis = options.axis.has_value();
  if (options.axis) std::copy(options.axis->data(), options.axis->data() + 3, command.axis);
  command.has_length = options.length.has_value();
  command.length = options.length.value_or(0.0);
  command.has_limits = options.limits.has_value();
  if (options.limits) {
    command.lower = options.limits->first;
    command.upper = options.limits->second;
  }
  command.has_damping = options.damping.has_value();
  command.damping = options.damping.value_or(0.0);
  command.has_friction = options.friction.has_value();
  command.friction = options.friction.value_or(0.0);
  command.collide_connected = options.collide_connected;
  return WithNewId(Send(command));
}

CommandResult Client::RemoveJoint(int64_t id) {
  joint_cmd_t command{};
  command.op = joint_cmd_t::REMOVE;
  command.joint_id = id;
  return Send(command);
}

CommandResult Client::Send(joint_cmd_t command) {
  command.client_id = options_.client_id;
  command.request_id = NextRequestId();
  std::vector<uint8_t> buffer(command.getEncodedSize());
  command.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return Publish(Channel(protocol::kJointCmd), command.request_id, buffer.data(),
                 static_cast<int>(buffer.size()));
}

}  // namespace contactsim
