#include "service/server/arm_driver/wsg_fingers.h"

#include <algorithm>

#include "service/server/arm_driver/arm_joints.h"

namespace contactsim {
namespace {

const ModelJointEntry* FindModelJoint(const ModelRecord& model, const std::string& name) {
  for (const ModelJointEntry& e : model.joints) {
    if (e.name == name) return &e;
  }
  return nullptr;
}

// One finger's joint, its opening side and its range of opening [lo, hi].
Status FindFinger(const World& world, const ModelRecord& model, const std::string& name, int i, WsgFingers* f,
                  double* lo, double* hi) {
  const ModelJointEntry* e = FindModelJoint(model, name);
  if (e == nullptr) return Status::NotFound("model \"" + model.name + "\" has no joint named \"" + name + "\"");
  const Joint* j = e->joint != 0 ? world.FindJoint(e->joint) : nullptr;
  if (j == nullptr || j->kind != JointKind::kPrismatic) {
    return Status::FailedPrecondition("finger joint \"" + name + "\" is " + e->type +
                                      "; a finger of the gripper needs a prismatic joint");
  }
  if (!j->limited || (j->lower < 0 && j->upper > 0)) {
    return Status::FailedPrecondition(
        "finger joint \"" + name + "\" needs limits on one side of 0 (0 the finger closed on the centre), got " +
        (j->limited ? "[" + std::to_string(j->lower) + ", " + std::to_string(j->upper) + "] m" : "none"));
  }
  f->joints[i] = j->id;
  f->sign[i] = j->upper > 0 ? 1.0 : -1.0;
  f->effort_limit[i] = LimitOrInfinity(e->effort_limit);
  // + 0.0: a closed limit of -0 reads 0
  *lo = std::min(f->sign[i] * j->lower, f->sign[i] * j->upper) + 0.0;
  *hi = std::max(f->sign[i] * j->lower, f->sign[i] * j->upper) + 0.0;
  return Status::Ok();
}

}  // namespace

Status FindWsgFingers(const World& world, const std::string& model, const std::string (&joints)[2],
                      WsgFingers* out) {
  const ModelRecord* record = FindModelNamed(world, model);
  if (record == nullptr) return Status::NotFound("the world holds no model named \"" + model + "\"");
  WsgFingers f;
  double lo[2], hi[2];
  for (int i = 0; i < 2; ++i) {
    const Status st = FindFinger(world, *record, joints[i], i, &f, &lo[i], &hi[i]);
    if (!st.ok()) return st;
  }
  // both fingers move to half the separation: it is reachable where both
  // ranges of opening overlap
  f.min_separation = 2 * std::max(lo[0], lo[1]);
  f.max_separation = 2 * std::min(hi[0], hi[1]);
  if (f.min_separation > f.max_separation) {
    return Status::FailedPrecondition("finger joints \"" + joints[0] + "\" and \"" + joints[1] +
                                      "\" have no opening in common");
  }
  *out = f;
  return Status::Ok();
}

void ReadWsgFingers(const World& world, const WsgFingers& fingers, double (&q)[2], double (&v)[2]) {
  for (int i = 0; i < 2; ++i) {
    const Joint& j = *world.FindJoint(fingers.joints[i]);
    const RigidBody& a = *world.Find(j.body_a);
    const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
    q[i] = JointPosition(j, a, b);
    v[i] = JointVelocity(j, a, b);
  }
}

void ReadWsgSeparation(const World& world, const WsgFingers& fingers, double* separation, double* speed) {
  double q[2], v[2];
  ReadWsgFingers(world, fingers, q, v);
  *separation = fingers.sign[0] * q[0] + fingers.sign[1] * q[1];
  *speed = fingers.sign[0] * v[0] + fingers.sign[1] * v[1];
}

}  // namespace contactsim
