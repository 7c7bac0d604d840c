#include "service/server/actuator_update.h"

#include <algorithm>
#include <set>

namespace contactsim {
namespace {

struct FieldColumn {
  uint8_t bit;
  const char* name;
  std::vector<double> joint_command_t::*column;
  double JointActuator::*member;
};

constexpr FieldColumn kColumns[] = {
    {kActuatorTorque, "torques", &joint_command_t::torques, &JointActuator::torque},
    {kActuatorTargetPosition, "target_positions", &joint_command_t::target_positions,
     &JointActuator::target_position},
    {kActuatorTargetVelocity, "target_velocities", &joint_command_t::target_velocities,
     &JointActuator::target_velocity},
    {kActuatorKp, "kp", &joint_command_t::kp, &JointActuator::kp},
    {kActuatorKd, "kd", &joint_command_t::kd, &JointActuator::kd},
    {kActuatorEffortLimit, "effort_limits", &joint_command_t::effort_limits, &JointActuator::effort_limit},
    {kActuatorVelocityLimit, "velocity_limits", &joint_command_t::velocity_limits,
     &JointActuator::velocity_limit},
};

}  // namespace

Status DecodeActuatorUpdate(const joint_command_t& m, ActuatorUpdate* u) {
  *u = ActuatorUpdate();
  if (m.num_joints == 0 && m.num_ids == 0 && m.model_id == 0) return Status::Ok();  // none
  if (m.fields < 0 || (m.fields & ~kActuatorAllFields) != 0) {
    return Status::InvalidArgument("joints.fields must be a bitwise or of TORQUE=1 .. VELOCITY_LIMIT=64, got " +
                                   std::to_string(m.fields));
  }
  if (m.model_id < 0) return Status::InvalidArgument("joints.model_id must be >= 0, got " + std::to_string(m.model_id));
  if (m.num_joints < 0 || m.num_ids < 0) return Status::InvalidArgument("joints: negative count");
  const size_t n = static_cast<size_t>(m.num_joints);
  if (m.num_ids != m.num_joints && !(m.model_id > 0 && m.num_ids == 0)) {
    return Status::InvalidArgument("joints: num_ids (" + std::to_string(m.num_ids) + ") must equal num_joints (" +
                                   std::to_string(m.num_joints) + "), or be 0 with a model_id");
  }
  u->fields = static_cast<uint8_t>(m.fields);
  u->model = m.model_id;
  u->joints.assign(m.joint_ids.begin(), m.joint_ids.end());
  u->values.resize(n);
  for (const FieldColumn& c : kColumns) {
    const std::vector<double>& col = m.*c.column;
    if (col.size() != n) return Status::InvalidArgument(std::string("joints.") + c.name + ": wrong length");
    if ((u->fields & c.bit) == 0) continue;
    for (size_t i = 0; i < n; ++i) u->values[i].*c.member = col[i];
  }
  // the fields given over an actuator of none (valid), checked as any actuator is
  for (size_t i = 0; i < n; ++i) {
    const Status st = CheckJointActuator(MergeActuator(JointActuator(), u->fields, u->values[i]));
    if (!st.ok()) return st.Prefixed("joints[" + std::to_string(i) + "].");
  }
  return Status::Ok();
}

joint_command_t EncodeActuatorUpdate(const ActuatorUpdate& u) {
  joint_command_t m;
  m.fields = static_cast<int8_t>(u.fields);
  m.model_id = u.model;
  m.num_ids = static_cast<int32_t>(u.joints.size());
  m.joint_ids = u.joints;
  m.num_joints = static_cast<int32_t>(u.values.size());
  for (const FieldColumn& c : kColumns) {
    std::vector<double>& col = m.*c.column;
    col.resize(u.values.size(), 0.0);
    if ((u.fields & c.bit) == 0) continue;
    for (size_t i = 0; i < u.values.size(); ++i) col[i] = u.values[i].*c.member;
  }
  return m;
}

std::vector<JointId> ModelCoordinateJoints(const World& world, const ModelRecord& model) {
  std::vector<JointId> out;
  for (const ModelJointEntry& e : model.joints) {
    const Joint* j = e.joint == 0 ? nullptr : world.FindJoint(e.joint);
    if (j != nullptr && HasJointCoordinate(j->kind)) out.push_back(e.joint);
  }
  return out;
}

Status ResolveActuatorUpdate(const World& world, ActuatorUpdate* u) {
  if (u->empty() && u->model == 0) return Status::Ok();
  std::vector<JointId> of_model;
  if (u->model != 0) {
    const auto it = std::find_if(world.models.begin(), world.models.end(),
                                 [u](const ModelRecord& m) { return m.id == u->model; });
    if (it == world.models.end()) return Status::NotFound("unknown model id " + std::to_string(u->model));
    of_model = ModelCoordinateJoints(world, *it);
    if (u->joints.empty() && u->values.empty()) u->values.resize(of_model.size());  // CLEAR of a whole model
    if (u->joints.empty()) {
      if (of_model.size() != u->values.size()) {
        return Status::InvalidArgument("model " + std::to_string(u->model) + " \"" + it->name + "\" has " +
                                       std::to_string(of_model.size()) + " joints with a coordinate, got " +
                                       std::to_string(u->values.size()) + " values");
      }
      u->joints = of_model;
    }
  }
  std::set<JointId> seen;
  for (JointId id : u->joints) {
    const Joint* j = world.FindJoint(id);
    if (j == nullptr) return Status::NotFound("unknown joint id " + std::to_string(id));
    if (!HasJointCoordinate(j->kind)) {
      return Status::FailedPrecondition("joint " + std::to_string(id) + " is a " + JointKindName(j->kind) +
                                        " joint: only hinge and prismatic joints take an actuator");
    }
    if (u->model != 0 && std::find(of_model.begin(), of_model.end(), id) == of_model.end()) {
      return Status::InvalidArgument("joint " + std::to_string(id) + " is not a joint of model " +
                                     std::to_string(u->model));
    }
    if (!seen.insert(id).second) return Status::InvalidArgument("joint " + std::to_string(id) + " is named twice");
  }
  u->model = 0;
  return Status::Ok();
}

JointActuator MergeActuator(const JointActuator& standing, uint8_t fields, const JointActuator& value) {
  JointActuator out = standing;
  for (const FieldColumn& c : kColumns) {
    if ((fields & c.bit) != 0) out.*c.member = value.*c.member;
  }
  return out;
}

}  // namespace contactsim
