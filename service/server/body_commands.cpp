// SimServer's body and joint commands (BODY_CMD, JOINT_CMD): the checks
// that need the world (does the body exist, is it dynamic, is there room)
// and the change itself. Simulation thread. A failed check changes nothing.
#include "service/contact/method_support.h"
#include "service/contact/sleep/island_sleep.h"
#include "service/physics/validation.h"
#include "service/server/sim_server.h"

namespace contactsim {

RigidBody* SimServer::FindBody(BodyId id, bool need_dynamic, Status* status) {
  RigidBody* b = world_.Find(id);
  if (b == nullptr) {
    *status = Status::NotFound("unknown body id " + std::to_string(id));
  } else if (need_dynamic && !b->IsDynamic()) {
    const char* what = b->motion == MotionType::kKinematic ? " is kinematic (infinite mass)" : " is static";
    *status = Status::FailedPrecondition("body " + std::to_string(id) + what);
    return nullptr;
  }
  return b;
}

Outcome SimServer::ApplyBodyCommand(Command& cmd) {
  using K = Command::Kind;
  const std::string body = "body " + std::to_string(cmd.body_id);
  Status st;
  switch (cmd.kind) {
    case K::kAddBody: {
      if (static_cast<int>(world_.bodies().size()) >= options_.max_bodies) {
        return Outcome::Failed(Status::ResourceExhausted("the world holds max_bodies = " +
                                                         std::to_string(options_.max_bodies) + " bodies already"));
      }
      const char* shape = ShapeTypeName(cmd.new_body.shape.type);
      if (!(st = CheckMethodAcceptsBody(method_->Name(), cmd.new_body, std::string("the new ") + shape)).ok()) {
        return Outcome::Failed(st);
      }
      const BodyId id = world_.AddBody(std::move(cmd.new_body));
      WakeTouching(world_, id);  // a body added into a sleeping pile, or under it
      detector_.Reset();
      std::string text = std::string("added ") + shape + " " + std::to_string(id);
      if (!cmd.reply_note.empty()) text += " (" + cmd.reply_note + ")";
      Outcome o = Outcome::Done(text, true);
      o.ids = {id};
      return o;
    }
    case K::kRemoveBody: {
      if (!(st = CheckNotInModel(cmd.body_id, 0)).ok()) return Outcome::Failed(st);
      const size_t joints = world_.joints().size();
      WakeTouching(world_, cmd.body_id);  // what rested on it, or against it
      if (!(st = world_.RemoveBody(cmd.body_id)).ok()) return Outcome::Failed(st);
      detector_.Reset();
      std::string text = "removed " + body;
      if (world_.joints().size() < joints) text += " and its " + std::to_string(joints - world_.joints().size()) + " joint(s)";
      return Outcome::Done(text, true);
    }
    case K::kAddJoint: {
      if (static_cast<int>(world_.joints().size()) >= options_.max_joints) {
        return Outcome::Failed(Status::ResourceExhausted("the world holds max_joints = " +
                                                         std::to_string(options_.max_joints) + " joints already"));
      }
      if (!(st = CheckMethodAcceptsJoint(method_->Name())).ok()) return Outcome::Failed(st);
      JointId id = 0;
      if (!(st = world_.AddJoint(cmd.joint, &id)).ok()) return Outcome::Failed(st);
      Outcome o = Outcome::Done(std::string("added ") + JointKindName(cmd.joint.kind) + " joint " + std::to_string(id), true);
      o.ids = {id};
      return o;
    }
    case K::kRemoveJoint:
      if (!(st = CheckNotInModel(0, cmd.joint_id)).ok()) return Outcome::Failed(st);
      if (!(st = world_.RemoveJoint(cmd.joint_id)).ok()) return Outcome::Failed(st);
      return Outcome::Done("removed joint " + std::to_string(cmd.joint_id), true);
    case K::kSetFilter:
      // World names the world (id 0) in its refusal; the change wakes the
      // body's island, and what touches it wakes here
      if (!(st = world_.SetCollisionFilter(cmd.body_id, cmd.collision_category, cmd.collision_mask,
                                           cmd.collision_group)).ok()) {
        return Outcome::Failed(st);
      }
      WakeTouching(world_, cmd.body_id);
      return Outcome::Done("collision filter of " + body + " set", true);
    default:
      break;
  }
  // the commands on one existing body
  const bool need_dynamic = cmd.kind == K::kApplyForce || cmd.kind == K::kApplyImpulse || cmd.kind == K::kSetMass;
  RigidBody* b = FindBody(cmd.body_id, need_dynamic, &st);
  if (b == nullptr) return Outcome::Failed(st);
  Outcome out = ApplyToBody(cmd, b);
  // every change of a body wakes it and what touches it (island_sleep.h):
  // no command is lost to sleep
  if (out.status.ok()) WakeTouching(world_, cmd.body_id);
  return out;
}

Outcome SimServer::ApplyToBody(Command& cmd, RigidBody* b) {
  using K = Command::Kind;
  const std::string body = "body " + std::to_string(cmd.body_id);
  Status st;
  switch (cmd.kind) {
    case K::kSetPose: {
      WakeTouching(world_, cmd.body_id);  // what rested on it where it was
      const Vec3 v = b->LinearVelocity(), w = b->AngularVelocity();
      b->x = cmd.position;
      b->q = cmd.orientation;
      b->SetVelocity(v, w);  // keep w, not L, across the rotation
      return Outcome::Done("pose of " + body + " set", true);
    }
    case K::kSetVelocity:
      if (b->motion == MotionType::kStatic) return Outcome::Failed(Status::FailedPrecondition(body + " is static"));
      b->SetVelocity(cmd.linear, cmd.angular);
      return Outcome::Done("velocity of " + body + " set", true);
    case K::kApplyForce:
      world_.AddWrench({cmd.body_id, cmd.linear, cmd.angular, cmd.duration});
      return Outcome::Done("force on " + body + " for " + FormatValue(cmd.duration) + " s", true);
    case K::kApplyImpulse:
      b->ApplyImpulse(cmd.linear, cmd.point.value_or(b->x));
      return Outcome::Done("impulse on " + body, true);
    case K::kSetMass:
      if (cmd.mass) b->SetMass(*cmd.mass);
      else b->SetMassFromDensity(*cmd.density);
      return Outcome::Done("mass of " + body + " is " + FormatValue(b->mass) + " kg", true);
    case K::kSetMaterial: {
      RigidBody changed = *b;  // checked before anything changes
      if (cmd.restitution) changed.material.restitution = *cmd.restitution;
      if (!(st = CheckMethodAcceptsBody(method_->Name(), changed, body)).ok()) return Outcome::Failed(st);
      if (cmd.restitution) b->material.restitution = *cmd.restitution;
      if (cmd.friction) b->material.friction = *cmd.friction;
      return Outcome::Done("material of " + body + " set", true);
    }
    default:
      return Outcome::Failed(Status::Internal("not a body command"));
  }
}

}  // namespace contactsim
