#include "service/physics/world.h"

#include "service/physics/fnv1a.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace contactsim {

BodyId World::AddBody(RigidBody body) {
  body.id = next_id++;
  bodies_.push_back(std::move(body));  // ids grow, so the vector stays sorted
  index_[bodies_.back().id] = static_cast<int>(bodies_.size()) - 1;
  return bodies_.back().id;
}

Status World::RemoveBody(BodyId id) {
  const int i = IndexOf(id);
  if (i < 0) return Status::NotFound("unknown body id " + std::to_string(id));
  WakeBody(id);  // its island loses a body (a support, a joint)
  bodies_.erase(bodies_.begin() + i);
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [id](const TimedWrench& w) { return w.body == id; }),
                  wrenches_.end());
  joints_.erase(std::remove_if(joints_.begin(), joints_.end(),
                               [id](const Joint& j) { return j.body_a == id || j.body_b == id; }),
                joints_.end());
  sensors.RemoveBody(id);
  Reindex();
  IndexJointPairs();
  DropOrphanMimics();
  return Status::Ok();
}

Status World::Assign(std::vector<RigidBody> bodies, std::vector<TimedWrench> wrenches, BodyId next) {
  BodyId last = 0;
  for (const RigidBody& b : bodies) {
    if (b.id <= last || b.id >= next) {
      return Status::InvalidArgument("body ids must ascend and stay below next_id " + std::to_string(next) +
                                     ", got " + std::to_string(b.id) + " after " + std::to_string(last));
    }
    last = b.id;
  }
  bodies_ = std::move(bodies);
  wrenches_ = std::move(wrenches);
  next_id = next;
  Reindex();
  return Status::Ok();
}

Status World::AssignJoints(std::vector<Joint> joints, JointId next) {
  JointId last = 0;
  for (const Joint& j : joints) {
    if (j.id <= last || j.id >= next) {
      return Status::InvalidArgument("joint ids must ascend and stay below next_joint_id " + std::to_string(next) +
                                     ", got " + std::to_string(j.id) + " after " + std::to_string(last));
    }
    if (Find(j.body_a) == nullptr || (j.body_b != kWorldBody && Find(j.body_b) == nullptr)) {
      return Status::InvalidArgument("joint " + std::to_string(j.id) + " refers to a missing body");
    }
    last = j.id;
  }
  for (const Joint& j : joints) {
    if (j.mimic.master == 0) continue;
    if (Status st = CheckJointMimic(joints, j.id, j.mimic); !st.ok()) return st;
  }
  joints_ = std::move(joints);
  next_joint_id = next;
  IndexJointPairs();
  return Status::Ok();
}

Status World::AddJoint(const JointSettings& settings, JointId* id) {
  Status st = CheckJointSettings(settings);
  if (!st.ok()) return st;
  const RigidBody* a = Find(settings.body_a);
  if (a == nullptr) return Status::NotFound("body_a: unknown body id " + std::to_string(settings.body_a));
  const RigidBody* b = nullptr;
  if (settings.body_b != kWorldBody) {
    b = Find(settings.body_b);
    if (b == nullptr) return Status::NotFound("body_b: unknown body id " + std::to_string(settings.body_b));
  }
  Joint joint;
  st = CreateJoint(settings, *a, b, &joint);
  if (!st.ok()) return st;
  WakeBody(settings.body_a);
  if (b != nullptr) WakeBody(settings.body_b);
  joint.id = next_joint_id++;
  joints_.push_back(joint);  // ids grow, so the vector stays sorted
  if (!joint.collide_connected && joint.body_b != kWorldBody) joined_.Add(joint.body_a, joint.body_b);
  *id = joint.id;
  return Status::Ok();
}

Status World::RemoveJoint(JointId id) {
  const auto it = std::find_if(joints_.begin(), joints_.end(), [id](const Joint& j) { return j.id == id; });
  if (it == joints_.end()) return Status::NotFound("unknown joint id " + std::to_string(id));
  WakeBody(it->body_a);
  if (it->body_b != kWorldBody) WakeBody(it->body_b);
  if (!it->collide_connected && it->body_b != kWorldBody) joined_.Remove(it->body_a, it->body_b);
  joints_.erase(it);
  DropOrphanMimics();
  return Status::Ok();
}

Status World::SetJointMimic(JointId follower, const JointMimic& mimic) {
  const auto it =
      std::find_if(joints_.begin(), joints_.end(), [follower](const Joint& j) { return j.id == follower; });
  if (it == joints_.end()) return Status::NotFound("unknown joint id " + std::to_string(follower));
  if (mimic.master != 0) {
    if (Status st = CheckJointMimic(joints_, follower, mimic); !st.ok()) return st;
  }
  it->mimic = mimic.master != 0 ? mimic : JointMimic();
  WakeBody(it->body_a);
  if (it->body_b != kWorldBody) WakeBody(it->body_b);
  return Status::Ok();
}

bool World::HasJointMimics() const {
  return std::any_of(joints_.begin(), joints_.end(), [](const Joint& j) { return j.mimic.master != 0; });
}

void World::DropOrphanMimics() {
  for (Joint& j : joints_) {
    if (j.mimic.master != 0 && FindJoint(j.mimic.master) == nullptr) j.mimic = JointMimic();
  }
}

Status World::SetJointActuator(JointId id, const JointActuator& actuator) {
  const auto it = std::find_if(joints_.begin(), joints_.end(), [id](const Joint& j) { return j.id == id; });
  if (it == joints_.end()) return Status::NotFound("unknown joint id " + std::to_string(id));
  if (!HasJointCoordinate(it->kind)) {
    return Status::FailedPrecondition("joint " + std::to_string(id) + " is a " + JointKindName(it->kind) +
                                      " joint: only hinge and prismatic joints take an actuator");
  }
  Status st = CheckJointActuator(actuator);
  if (!st.ok()) return st.Prefixed("joint " + std::to_string(id) + ": ");
  it->actuator = actuator;
  WakeBody(it->body_a);
  if (it->body_b != kWorldBody) WakeBody(it->body_b);
  return Status::Ok();
}

Status World::SetCollisionFilter(BodyId id, uint32_t category, uint32_t mask, int32_t group) {
  RigidBody* b = Find(id);
  if (b == nullptr) {
    return Status::NotFound(id == kWorldBody ? std::string("body id 0 is the world, which has no collision filter")
                                             : "unknown body id " + std::to_string(id));
  }
  WakeBody(id);
  b->collision_category = category;
  b->collision_mask = mask;
  b->collision_group = group;
  return Status::Ok();
}

const Joint* World::FindJoint(JointId id) const {
  const auto it = std::find_if(joints_.begin(), joints_.end(), [id](const Joint& j) { return j.id == id; });
  return it == joints_.end() ? nullptr : &*it;
}

RigidBody* World::Find(BodyId id) {
  const int i = IndexOf(id);
  return i < 0 ? nullptr : &bodies_[i];
}

const RigidBody* World::Find(BodyId id) const {
  const int i = IndexOf(id);
  return i < 0 ? nullptr : &bodies_[i];
}

int World::IndexOf(BodyId id) const {
  // ids grow with the index (AddBody), and until a body is removed they are
  // consecutive: body i has the first body's id + i, found without the map
  // (the joint rows look their bodies up several times a step)
  // (a client may send any id: the offset is taken only above the first id,
  // in unsigned arithmetic, so that no id overflows the subtraction)
  if (!bodies_.empty() && id >= bodies_.front().id) {
    const uint64_t guess = static_cast<uint64_t>(id) - static_cast<uint64_t>(bodies_.front().id);
    if (guess < bodies_.size() && bodies_[guess].id == id) return static_cast<int>(guess);
  }
  const auto it = index_.find(id);
  return it == index_.end() ? -1 : it->second;
}

void World::AddWrench(const TimedWrench& wrench) {
  WakeBody(wrench.body);
  wrenches_.push_back(wrench);
}

void World::WakeBody(BodyId id) {
  RigidBody* b = Find(id);
  if (b == nullptr) return;
  if (b->asleep()) WakeIsland(b->sleep_island);
  b->rest_time = 0.0;
}

void World::WakeIsland(BodyId island) {
  if (island == 0) return;
  for (RigidBody& b : bodies_) {
    if (b.sleep_island != island) continue;
    b.sleep_island = 0;
    b.rest_time = 0.0;
  }
}

void World::WakeAll() {
  for (RigidBody& b : bodies_) {
    b.sleep_island = 0;
    b.rest_time = 0.0;
  }
}

int World::SleepingCount() const {
  int n = 0;
  for (const RigidBody& b : bodies_) n += b.asleep() ? 1 : 0;
  return n;
}

void World::AccumulateForces() {
  for (RigidBody& b : bodies_) {
    b.force = b.IsDynamic() ? Vec3(b.mass * gravity) : Vec3::Zero();
    b.torque.setZero();
  }
  for (const TimedWrench& w : wrenches_) {
    RigidBody* b = Find(w.body);
    if (b == nullptr || !b->IsDynamic()) continue;
    // A wrench ending inside this step acts for its remaining fraction only,
    // so the impulse delivered is exactly F * duration.
    const double fraction = w.remaining > 0.0 ? std::min(1.0, w.remaining / dt) : 1.0;
    b->force += fraction * w.force;
    b->torque += fraction * w.torque;
  }
  for (Joint& j : joints_) ApplyFeedForward(j);
}

void World::ApplyFeedForward(Joint& j) {
  // an actuator with gains is a drive row of the contact method, which
  // records its effort; one without applies its torque here
  j.effort = 0.0;
  if (!IsActuated(j.actuator) || HasDriveGains(j.actuator)) return;
  RigidBody* a = Find(j.body_a);
  RigidBody* b = j.body_b == kWorldBody ? nullptr : Find(j.body_b);
  if (a == nullptr || (!a->IsDynamic() && (b == nullptr || !b->IsDynamic()))) return;
  j.effort = ClampEffort(j.actuator, j.actuator.torque);
  // J^T u of the coordinate's row (joint_rows.h): a hinge turns B by +a u
  // and A by -a u; a slider pushes B's anchor along +a and A, at that same
  // point, along -a (s = a . (p_B - p_A), the lever arm of A reaching p_B)
  const Vec3 axis = a->q * j.axis_a;
  if (j.kind == JointKind::kHinge) {
    if (a->IsDynamic()) a->torque -= j.effort * axis;
    if (b != nullptr && b->IsDynamic()) b->torque += j.effort * axis;
    return;
  }
  const Vec3 p_b = AnchorWorld(j.anchor_b, b);
  const Vec3 f = j.effort * axis;
  if (a->IsDynamic()) a->force -= f, a->torque -= (p_b - a->x).cross(f);
  if (b != nullptr && b->IsDynamic()) b->force += f, b->torque += (p_b - b->x).cross(f);
}

void World::FinishStep() {
  time += dt;
  ++step;
  for (TimedWrench& w : wrenches_) w.remaining -= dt;
  // A zero-duration wrench acted once; a timed one until its time ran out
  // (the relative slack absorbs round-off in repeated subtraction).
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [this](const TimedWrench& w) { return w.remaining <= 1e-9 * dt; }),
                  wrenches_.end());
}

void World::Clear() {
  bodies_.clear();
  index_.clear();
  wrenches_.clear();
  joints_.clear();
  joined_.Clear();
  sensors.Clear();
  gravity = DefaultGravity();
  dt = kDefaultDt;
  time = 0.0;
  step = 0;
  next_id = 1;
  next_joint_id = 1;
  models.clear();
  next_model_id = 1;
}

void World::Reindex() {
  index_.clear();
  for (int i = 0; i < static_cast<int>(bodies_.size()); ++i) index_[bodies_[i].id] = i;
}

void World::IndexJointPairs() {
  joined_.Clear();
  for (const Joint& j : joints_) {
    if (!j.collide_connected && j.body_b != kWorldBody) joined_.Add(j.body_a, j.body_b);
  }
}

uint64_t HashWorldState(const World& world) {
  Fnv1a f;
  f.Double(world.time);
  f.Bytes(&world.step, sizeof world.step);
  for (const RigidBody& b : world.bodies()) {
    f.Bytes(&b.id, sizeof b.id);
    f.Vector(b.x);
    f.Double(b.q.w());
    f.Vector(b.q.vec());
    f.Vector(b.P);
    f.Vector(b.L);
    if (world.sleep.enabled) {
      f.Double(b.rest_time);
      f.Bytes(&b.sleep_island, sizeof b.sleep_island);
    }
  }
  for (const Joint& j : world.joints()) {
    const int kind = static_cast<int>(j.kind);
    f.Bytes(&j.id, sizeof j.id);
    f.Bytes(&kind, sizeof kind);
    f.Bytes(&j.body_a, sizeof j.body_a);
    f.Bytes(&j.body_b, sizeof j.body_b);
    for (const Vec3& v : {j.anchor_a, j.anchor_b, j.axis_a, j.axis_b, Vec3(j.rest.vec())}) f.Vector(v);
    f.Double(j.rest.w());
    f.Double(j.length);
    f.Bytes(&j.limited, sizeof j.limited);
    f.Double(j.lower);
    f.Double(j.upper);
    // only when set, so that the hash of a world without them is unchanged
    if (j.damping != 0.0 || j.friction != 0.0) {
      f.Double(j.damping);
      f.Double(j.friction);
    }
    if (j.collide_connected) f.Bytes(&j.collide_connected, sizeof j.collide_connected);
    // only for an actuated joint (IsActuated: a torque or a gain), so that
    // the hash of a world without actuators is unchanged, and a model's
    // limits on a joint nobody drives (which move nothing) add nothing; the
    // effort is an output of the step, not state
    const JointActuator& act = j.actuator;
    if (IsActuated(act)) {
      for (double v : {act.torque, act.target_position, act.target_velocity, act.kp, act.kd, act.effort_limit,
                       act.velocity_limit}) {
        f.Double(v);
      }
    }
    if (j.mimic.master != 0) {
      f.Bytes(&j.mimic.master, sizeof j.mimic.master);
      f.Double(j.mimic.multiplier);
      f.Double(j.mimic.offset);
    }
  }
  return f.h;
}

double KineticEnergy(const World& world) {
  double e = 0.0;
  for (const RigidBody& b : world.bodies()) e += b.KineticEnergy();  // 0 for static and kinematic bodies
  return e;
}

double PotentialEnergy(const World& world) {
  double e = 0.0;
  for (const RigidBody& b : world.bodies()) {
    if (b.IsDynamic()) e -= b.mass * world.gravity.dot(b.x);
  }
  return e;
}

}  // namespace contactsim
