#include "service/model/model_adder.h"

#include <algorithm>

#include "service/model/engine_settings.h"
#include "service/physics/hull_memo.h"

namespace contactsim::model {
namespace {

// The link's frame in its body's frame, from both world poses at q = 0:
// p_body = R_body^T (p_link - x_body), R = R_body^T R_link.
void SetLinkFrame(const Pose& link_W, const RigidBody& body, ModelLinkEntry* e) {
  e->body = body.id;
  e->position = body.q.conjugate() * (link_W.position - body.x);
  e->orientation = (body.q.conjugate() * link_W.orientation).normalized();
}

}  // namespace

Status PrepareModel(ModelBuild build, const World& world, const Material& default_material, PreparedModel* out) {
  const std::string& name = build.record.name;
  for (const ModelRecord& m : world.models) {
    if (m.name == name) {
      return Status::FailedPrecondition("a model named \"" + name + "\" is loaded already (model " +
                                        std::to_string(m.id) + "); give the new one another name");
    }
  }
  PreparedModel p;
  // one negative group per model, named by its id: its bodies never collide
  // with each other unless it asks for self-collision
  const int group = -static_cast<int>(world.next_model_id % 1000000000);
  HullMemo memo;  // links that share a mesh or a cylinder's size build its hull once
  for (size_t i = 0; i < build.bodies.size(); ++i) {
    RigidBody b;
    Status st = ApplySelfCollision(build.record.self_collide, group, &build.bodies[i].settings);
    if (st.ok()) st = CreateBody(build.bodies[i].settings, default_material, &b, &memo);
    if (!st.ok()) {
      return Status::InvalidArgument("model \"" + name + "\", link \"" + build.record.links[build.bodies[i].link].name +
                                     "\": " + st.message());
    }
    b.id = world.next_id + static_cast<BodyId>(i);
    p.bodies.push_back(std::move(b));
  }
  for (const BuiltJoint& bj : build.joints) {
    JointSettings s = bj.settings;
    s.body_a = p.bodies[bj.body_a].id;
    s.body_b = p.bodies[bj.body_b].id;
    Joint check;
    Status st = CreateJoint(s, p.bodies[bj.body_a], &p.bodies[bj.body_b], &check);
    if (st.ok()) st = CheckJointActuator(bj.actuator);
    if (!st.ok()) {
      return Status::InvalidArgument("model \"" + name + "\", joint \"" + build.record.joints[bj.joint].name +
                                     "\": " + st.message());
    }
    p.joints.push_back(s);
  }
  p.build = std::move(build);
  *out = std::move(p);
  return Status::Ok();
}

Status CommitModel(PreparedModel p, World* world, ModelRecord* record) {
  if (!p.bodies.empty() && p.bodies.front().id != world->next_id) {
    return Status::Internal("model \"" + p.build.record.name + "\" was prepared for another world");
  }
  ModelRecord r = std::move(p.build.record);
  std::vector<BodyId> ids;
  for (RigidBody& b : p.bodies) ids.push_back(world->AddBody(std::move(b)));
  for (size_t i = 0; i < p.joints.size(); ++i) {
    JointId id = 0;
    if (Status st = world->AddJoint(p.joints[i], &id); !st.ok()) {
      for (BodyId b : ids) world->RemoveBody(b);  // cannot happen after PrepareModel; never leave half a model
      return Status::Internal("model \"" + r.name + "\": " + st.message());
    }
    if (Status st = world->SetJointActuator(id, p.build.joints[i].actuator); !st.ok()) {
      for (BodyId b : ids) world->RemoveBody(b);  // checked in PrepareModel: cannot happen
      return Status::Internal("model \"" + r.name + "\": " + st.message());
    }
    r.joints[p.build.joints[i].joint].joint = id;
  }
  for (const BuiltJoint& bj : p.build.joints) {
    if (bj.mimic_of < 0) continue;
    JointMimic mimic = bj.mimic;
    mimic.master = r.joints[p.build.joints[bj.mimic_of].joint].joint;
    if (Status st = world->SetJointMimic(r.joints[bj.joint].joint, mimic); !st.ok()) {
      for (BodyId b : ids) world->RemoveBody(b);  // checked by CheckMimics: cannot happen
      return Status::Internal("model "" + r.name + "": " + st.message());
    }
  }
  for (size_t li = 0; li < r.links.size(); ++li) {
    SetLinkFrame(p.build.link_pose_W[li], *world->Find(ids[p.build.link_body[li]]), &r.links[li]);
  }
  r.id = world->next_model_id++;
  world->models.push_back(r);
  *record = std::move(r);
  return Status::Ok();
}

Status RemoveModel(ModelId id, World* world, ModelRecord* removed) {
  auto it = std::find_if(world->models.begin(), world->models.end(), [id](const ModelRecord& m) { return m.id == id; });
  if (it == world->models.end()) return Status::NotFound("unknown model id " + std::to_string(id));
  std::vector<BodyId> bodies;
  for (const ModelLinkEntry& l : it->links) bodies.push_back(l.body);
  std::sort(bodies.begin(), bodies.end());
  bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
  for (BodyId b : bodies) world->RemoveBody(b);  // and the joints on them
  *removed = std::move(*it);
  world->models.erase(it);
  return Status::Ok();
}

const ModelRecord* FindModel(const World& world, ModelId id) {
  for (const ModelRecord& m : world.models) {
    if (m.id == id) return &m;
  }
  return nullptr;
}

const ModelRecord* ModelOfBody(const World& world, BodyId body) {
  for (const ModelRecord& m : world.models) {
    for (const ModelLinkEntry& l : m.links) {
      if (l.body == body) return &m;
    }
  }
  return nullptr;
}

}  // namespace contactsim::model
