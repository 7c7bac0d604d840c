// Joints' actuators: the SimServer methods of ACTUATOR_CMD, of a lockstep
// input's joint commands, and of JOINT_STATE (sim_server.h;
// docs/actuators.md, "Joint channels").
#include <contactsim/protocol.hpp>

#include <algorithm>

#include "service/server/joint_state_message.h"
#include "service/server/sim_server.h"

namespace contactsim {

// Checked in full before anything changes: a refused command leaves every
// joint as it was.
Outcome SimServer::ApplyActuatorCommand(Command& cmd) {
  if (cmd.kind == Command::Kind::kJointStateQuery) {
    publisher_.Publish(publisher_.Channel(protocol::kJointState), MakeJointStateMessage(world_));
    return Outcome::Done("joint state on " + publisher_.Channel(protocol::kJointState), false);
  }
  ActuatorUpdate& u = cmd.actuators;
  Status st = ResolveActuatorUpdate(world_, &u);
  if (!st.ok()) return Outcome::Failed(st);
  const bool clear = cmd.kind == Command::Kind::kClearActuators;
  std::vector<JointActuator> next(u.joints.size());
  for (size_t i = 0; i < u.joints.size(); ++i) {
    const JointActuator standing = world_.FindJoint(u.joints[i])->actuator;
    next[i] = clear ? JointActuator() : MergeActuator(standing, u.fields, u.values[i]);
    if (!(st = CheckJointActuator(next[i])).ok()) {
      return Outcome::Failed(st.Prefixed("joint " + std::to_string(u.joints[i]) + ": "));
    }
  }
  for (size_t i = 0; i < u.joints.size(); ++i) {
    if (!(st = world_.SetJointActuator(u.joints[i], next[i])).ok()) return Outcome::Failed(Status::Internal(st.message()));
  }
  Outcome o = Outcome::Done(std::string(clear ? "cleared" : "set") + " the actuators of " +
                                std::to_string(u.joints.size()) + " joints",
                            true);
  o.ids.assign(u.joints.begin(), u.joints.end());
  return o;
}

// At arrival: refused unless every joint exists and takes an actuator, so
// that the controller hears of it and the step waits for a good input.
Status SimServer::CheckInputJoints(ControllerInput* input) const {
  const Status st = ResolveActuatorUpdate(world_, &input->joints);
  return st.ok() ? st : st.Prefixed("input for step " + std::to_string(input->step) + ": ");
}

// The input's fields over each joint's standing settings, for this one step.
// A joint removed since the input arrived is skipped (a live input's sender
// hears of it), as a body is.
void SimServer::ApplyInputJoints(const ControllerInput& in, bool live) {
  const ActuatorUpdate& u = in.joints;
  for (size_t i = 0; i < u.joints.size(); ++i) {
    const Joint* j = world_.FindJoint(u.joints[i]);
    const JointActuator standing = j == nullptr ? JointActuator() : j->actuator;
    const Status st = j == nullptr ? Status::NotFound("unknown joint id " + std::to_string(u.joints[i]))
                                   : world_.SetJointActuator(u.joints[i], MergeActuator(standing, u.fields, u.values[i]));
    if (!st.ok()) {
      if (live) {
        batch_.SendReply(in.controller, in.request_id,
                         st.Prefixed("input for step " + std::to_string(in.step) + ": "), "");
      }
      continue;
    }
    const bool saved = std::any_of(standing_actuators_.begin(), standing_actuators_.end(),
                                   [&](const auto& s) { return s.first == u.joints[i]; });
    if (!saved) standing_actuators_.emplace_back(u.joints[i], standing);
  }
}

void SimServer::RestoreStandingActuators() {
  for (const auto& [id, standing] : standing_actuators_) {
    if (world_.FindJoint(id) != nullptr) world_.SetJointActuator(id, standing);
  }
  standing_actuators_.clear();
}

// Lockstep controllers read the joints from STATE: JOINT_STATE beside it
// would be a second datagram a step that wakes every socket on the group
// (docs/actuators.md, "Joint channels"; BENCHMARKS.md, "Lockstep: one
// datagram each way", has the measurements).
void SimServer::PublishJointState() {
  const JointStatePolicy policy = options_.joint_state;
  if (policy == JointStatePolicy::kOff) return;
  if (policy == JointStatePolicy::kOutsideLockstep && mode_ == RunMode::kLockstep && lockstep_.active()) return;
  if (!HasCoordinateJoints(world_)) return;
  publisher_.Publish(publisher_.Channel(protocol::kJointState), MakeJointStateMessage(world_));
}

}  // namespace contactsim
