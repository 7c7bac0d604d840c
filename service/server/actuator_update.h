// Changes to joints' actuator settings (service/physics/joint_actuator.h) as
// joint_command_t carries them, on ACTUATOR_CMD (standing settings) and in a
// lockstep input (one step): which joints, which fields, their values
// (docs/actuators.md, "Joint channels").
#pragma once

#include <contactsim/joint_command_t.hpp>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "service/physics/joint.h"
#include "service/physics/model_record.h"
#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

// The bits of joint_command_t::fields.
enum ActuatorField : uint8_t {
  kActuatorTorque = 1,
  kActuatorTargetPosition = 2,
  kActuatorTargetVelocity = 4,
  kActuatorKp = 8,
  kActuatorKd = 16,
  kActuatorEffortLimit = 32,
  kActuatorVelocityLimit = 64,
  kActuatorAllFields = 127,
};

struct ActuatorUpdate {
  uint8_t fields = 0;                 // ActuatorField bits: what changes
  ModelId model = 0;                  // 0: `joints` are world joint ids
  std::vector<JointId> joints;        // with a model and empty: its joints with a coordinate
  std::vector<JointActuator> values;  // one per joint; only the fields set are read
  bool empty() const { return values.empty(); }
};

// The checks that need no world: known field bits, as many ids as values
// (or none with a model), and each joint's fields as CheckJointActuator
// checks an actuator. A message without joints decodes to an empty update.
// The message names the joint's index, the field and the value.
Status DecodeActuatorUpdate(const joint_command_t& msg, ActuatorUpdate* update);
// The update as a message (a resolved one carries its joint ids).
joint_command_t EncodeActuatorUpdate(const ActuatorUpdate& update);

// The joints of a model that have a coordinate (hinge, prismatic), in the
// model's order: the order of JOINT_STATE and of a model's joint commands.
std::vector<JointId> ModelCoordinateJoints(const World& world, const ModelRecord& model);

// Checks the update against the world: the model exists, every joint exists,
// belongs to the model (when one is named), has a coordinate and appears
// once, and the counts agree. On success `update` names its joints
// explicitly (model 0), so that it means the same whatever the world's
// models are later.
Status ResolveActuatorUpdate(const World& world, ActuatorUpdate* update);

// `standing` with the fields of `update` set from `value`.
JointActuator MergeActuator(const JointActuator& standing, uint8_t fields, const JointActuator& value);

}  // namespace contactsim
