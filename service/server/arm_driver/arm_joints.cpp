#include "service/server/arm_driver/arm_joints.h"

#include <algorithm>
#include <limits>

namespace contactsim {
namespace {

// The model's world joints as (parent body, child body) pairs.
std::vector<std::pair<BodyId, BodyId>> ModelEdges(const World& world, const ModelRecord& model) {
  std::vector<std::pair<BodyId, BodyId>> edges;
  for (const ModelJointEntry& e : model.joints) {
    if (const Joint* j = e.joint != 0 ? world.FindJoint(e.joint) : nullptr) edges.emplace_back(j->body_a, j->body_b);
  }
  return edges;
}

// The dynamic bodies reached from `child` through the edges without
// passing `parent`: what a joint between them carries.
std::vector<BodyId> Outboard(const World& world, const std::vector<std::pair<BodyId, BodyId>>& edges, BodyId parent,
                             BodyId child) {
  std::vector<BodyId> seen{parent, child};
  std::vector<BodyId> todo{child};
  while (!todo.empty()) {
    const BodyId b = todo.back();
    todo.pop_back();
    for (const auto& [a, c] : edges) {
      const BodyId other = a == b ? c : (c == b ? a : 0);
      if (other == 0 || std::find(seen.begin(), seen.end(), other) != seen.end()) continue;
      seen.push_back(other);
      todo.push_back(other);
    }
  }
  std::vector<BodyId> out;
  for (size_t i = 1; i < seen.size(); ++i) {
    const RigidBody* body = world.Find(seen[i]);
    if (body != nullptr && body->IsDynamic()) out.push_back(seen[i]);
  }
  return out;
}

}  // namespace

double LimitOrInfinity(double limit) { return limit > 0 ? limit : std::numeric_limits<double>::infinity(); }

const ModelRecord* FindModelNamed(const World& world, const std::string& name) {
  for (const ModelRecord& m : world.models) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

Status FindArmJoints(const World& world, const std::string& model, int count, ArmJoints* out) {
  const ModelRecord* record = FindModelNamed(world, model);
  if (record == nullptr) return Status::NotFound("the world holds no model named \"" + model + "\"");
  ArmJoints arm;
  arm.model = record->id;
  const auto edges = ModelEdges(world, *record);
  for (const ModelJointEntry& e : record->joints) {
    const Joint* j = e.joint != 0 ? world.FindJoint(e.joint) : nullptr;
    if (j == nullptr || j->kind != JointKind::kHinge || static_cast<int>(arm.joints.size()) == count) continue;
    arm.joints.push_back(j->id);
    arm.outboard.push_back(Outboard(world, edges, j->body_a, j->body_b));
    arm.effort_limit.push_back(LimitOrInfinity(e.effort_limit));
    arm.velocity_limit.push_back(LimitOrInfinity(e.velocity_limit));
  }
  if (static_cast<int>(arm.joints.size()) < count) {
    return Status::FailedPrecondition("model \"" + model + "\" has " + std::to_string(arm.joints.size()) +
                                      " hinge joints; the arm driver needs " + std::to_string(count));
  }
  for (const ModelLinkEntry& l : record->links) {
    const RigidBody* b = world.Find(l.body);
    if (b != nullptr && b->IsDynamic() && std::find(arm.bodies.begin(), arm.bodies.end(), l.body) == arm.bodies.end()) {
      arm.bodies.push_back(l.body);
    }
  }
  *out = std::move(arm);
  return Status::Ok();
}

void ReadArmJoints(const World& world, const ArmJoints& arm, std::vector<double>* position,
                   std::vector<double>* velocity) {
  position->clear();
  velocity->clear();
  for (JointId id : arm.joints) {
    const Joint& j = *world.FindJoint(id);
    const RigidBody& a = *world.Find(j.body_a);
    const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
    position->push_back(JointPosition(j, a, b));
    velocity->push_back(JointVelocity(j, a, b));
  }
}

std::vector<double> JointAxisTorques(const World& world, const ArmJoints& arm,
                                     const std::function<BodyLoad(BodyId)>& load) {
  std::vector<double> tau;
  for (size_t i = 0; i < arm.joints.size(); ++i) {
    const Joint& j = *world.FindJoint(arm.joints[i]);
    const RigidBody* child = world.Find(j.body_b);
    const Vec3 p_W = AnchorWorld(j.anchor_b, child);
    const Vec3 a_W = BodyOrientation(child) * j.axis_b;
    Vec3 moment = Vec3::Zero();
    for (BodyId id : arm.outboard[i]) {
      const BodyLoad l = load(id);
      moment += (world.Find(id)->x - p_W).cross(l.force) + l.torque;
    }
    tau.push_back(a_W.dot(moment));
  }
  return tau;
}

std::vector<double> GravityHoldTorques(const World& world, const ArmJoints& arm) {
  // the drives hold what gravity's loads would turn: the negated axis torques
  return JointAxisTorques(world, arm, [&](BodyId id) {
    return BodyLoad{-world.Find(id)->mass * world.gravity, Vec3::Zero()};
  });
}

void CompensateGravity(const ArmJoints& arm, World* world) {
  for (BodyId id : arm.bodies) {
    const RigidBody& b = *world->Find(id);
    world->AddWrench({id, -b.mass * world->gravity, Vec3::Zero(), 0.0});
  }
}

}  // namespace contactsim
