#include "service/server/joint_state_message.h"

#include <algorithm>
#include <set>
#include <string>

#include "service/server/actuator_update.h"

namespace contactsim {
namespace {

// One joint with a coordinate, as both messages carry it.
struct JointReading {
  const Joint* joint;
  ModelId model;
  const std::string* name;  // the model file's; nullptr for a joint of no model
  double position, velocity;
};

JointReading Read(const World& world, const Joint& j, ModelId model, const std::string* name) {
  const RigidBody* a = world.Find(j.body_a);
  const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
  return {&j, model, name, a == nullptr ? 0.0 : JointPosition(j, *a, b), a == nullptr ? 0.0 : JointVelocity(j, *a, b)};
}

// Calls visit(reading) for every joint with a coordinate, in the channel order.
template <typename Visit>
void ForEachCoordinateJoint(const World& world, Visit visit) {
  std::set<JointId> in_model;
  for (const ModelRecord& r : world.models) {
    for (const ModelJointEntry& e : r.joints) {
      const Joint* j = e.joint == 0 ? nullptr : world.FindJoint(e.joint);
      if (j == nullptr || !HasJointCoordinate(j->kind)) continue;
      visit(Read(world, *j, r.id, &e.name));
      in_model.insert(j->id);
    }
  }
  for (const Joint& j : world.joints()) {
    if (HasJointCoordinate(j.kind) && in_model.count(j.id) == 0) visit(Read(world, j, 0, nullptr));
  }
}

}  // namespace

joint_state_t MakeJointStateMessage(const World& world) {
  joint_state_t m;
  m.time = world.time;
  m.step = world.step;
  ForEachCoordinateJoint(world, [&m](const JointReading& r) {
    m.joint_ids.push_back(r.joint->id);
    m.model_ids.push_back(r.model);
    m.names.push_back(r.name != nullptr ? *r.name : std::to_string(r.joint->id));
    m.positions.push_back(r.position);
    m.velocities.push_back(r.velocity);
    m.efforts.push_back(r.joint->effort);
  });
  m.num_joints = static_cast<int32_t>(m.joint_ids.size());
  return m;
}

void FillStateJoints(const World& world, state_t* msg) {
  msg->joint_ids.clear();
  msg->joint_model_ids.clear();
  msg->joint_positions.clear();
  msg->joint_velocities.clear();
  msg->joint_efforts.clear();
  ForEachCoordinateJoint(world, [msg](const JointReading& r) {
    msg->joint_ids.push_back(r.joint->id);
    msg->joint_model_ids.push_back(r.model);
    msg->joint_positions.push_back(r.position);
    msg->joint_velocities.push_back(r.velocity);
    msg->joint_efforts.push_back(r.joint->effort);
  });
  msg->num_joints = static_cast<int32_t>(msg->joint_ids.size());
}

bool HasCoordinateJoints(const World& world) {
  return std::any_of(world.joints().begin(), world.joints().end(),
                     [](const Joint& j) { return HasJointCoordinate(j.kind); });
}

}  // namespace contactsim
