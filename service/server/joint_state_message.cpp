#include "service/server/joint_state_message.h"

#include <set>
#include <string>

#include "service/server/actuator_update.h"

namespace contactsim {
namespace {

void AddJoint(const World& world, const Joint& j, ModelId model, const std::string& name, joint_state_t* m) {
  const RigidBody* a = world.Find(j.body_a);
  const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
  m->joint_ids.push_back(j.id);
  m->model_ids.push_back(model);
  m->names.push_back(name);
  m->positions.push_back(a == nullptr ? 0.0 : JointPosition(j, *a, b));
  m->velocities.push_back(a == nullptr ? 0.0 : JointVelocity(j, *a, b));
  m->efforts.push_back(j.effort);
}

}  // namespace

joint_state_t MakeJointStateMessage(const World& world) {
  joint_state_t m;
  m.time = world.time;
  m.step = world.step;
  std::set<JointId> in_model;
  for (const ModelRecord& r : world.models) {
    for (const ModelJointEntry& e : r.joints) {
      const Joint* j = e.joint == 0 ? nullptr : world.FindJoint(e.joint);
      if (j == nullptr || !HasJointCoordinate(j->kind)) continue;
      AddJoint(world, *j, r.id, e.name, &m);
      in_model.insert(j->id);
    }
  }
  for (const Joint& j : world.joints()) {
    if (HasJointCoordinate(j.kind) && in_model.count(j.id) == 0) AddJoint(world, j, 0, std::to_string(j.id), &m);
  }
  m.num_joints = static_cast<int32_t>(m.joint_ids.size());
  return m;
}

}  // namespace contactsim
