// SimServer's model commands (MODEL_CMD, docs/models.md): a LOAD builds the
// model read by the decoder into bodies and joints and adds them all or
// none, after the server's limits and the contact method's contract; a
// REMOVE takes a model's bodies and joints out together; INFO asks for
// MODEL_INFO now. Simulation thread. A failed check changes nothing.
#include "service/contact/method_support.h"
#include "service/contact/sleep/island_sleep.h"
#include "service/model/model_adder.h"
#include "service/physics/fnv1a.h"
#include "service/server/messages.h"
#include "service/server/sim_server.h"

namespace contactsim {
namespace {

// A room check: the world holds `have`, the model adds `more`, the limit is `max`.
Status CheckRoom(const char* what, size_t have, size_t more, int max) {
  if (have + more <= static_cast<size_t>(max)) return Status::Ok();
  return Status::ResourceExhausted(std::string("the model's ") + std::to_string(more) + " " + what +
                                   " do not fit: the world holds " + std::to_string(have) + " of max_" + what + " = " +
                                   std::to_string(max));
}

// reply.ids of a LOAD: the model id, each link's body, each joint's id (0
// when merged or floating), in the file's order
std::vector<int64_t> LoadIds(const ModelRecord& r) {
  std::vector<int64_t> ids = {r.id};
  for (const ModelLinkEntry& l : r.links) ids.push_back(l.body);
  for (const ModelJointEntry& j : r.joints) ids.push_back(j.joint);
  return ids;
}

}  // namespace

Outcome SimServer::LoadModel(Command& cmd) {
  model::ModelBuild build;
  Status st = model::BuildModel(*cmd.model, cmd.model_options, &build);
  if (st.ok()) st = CheckRoom("bodies", world_.bodies().size(), build.bodies.size(), options_.max_bodies);
  if (st.ok()) st = CheckRoom("joints", world_.joints().size(), build.joints.size(), options_.max_joints);
  model::PreparedModel prepared;
  if (st.ok()) st = model::PrepareModel(std::move(build), world_, cmd.model_material, &prepared);
  for (size_t i = 0; st.ok() && i < prepared.bodies.size(); ++i) {
    const std::string what = "model \"" + prepared.build.record.name + "\", link \"" +
                             prepared.build.record.links[prepared.build.bodies[i].link].name + "\"";
    st = CheckMethodAcceptsBody(method_->Name(), prepared.bodies[i], what);
  }
  if (st.ok() && !prepared.joints.empty()) st = CheckMethodAcceptsJoint(method_->Name());
  for (const model::BuiltJoint& bj : prepared.build.joints) {
    if (st.ok() && bj.mimic_of >= 0) st = CheckMethodAcceptsMimic(method_->Name());
  }
  ModelRecord record;
  if (st.ok()) st = model::CommitModel(std::move(prepared), &world_, &record);
  if (!st.ok()) return Outcome::Failed(st);
  for (const ModelLinkEntry& l : record.links) WakeTouching(world_, l.body);  // loaded into a sleeping pile
  detector_.Reset();
  Outcome o = Outcome::Done("loaded model \"" + record.name + "\" " + std::to_string(record.id) + ": " +
                                std::to_string(record.links.size()) + " links, " +
                                std::to_string(record.joints.size()) + " joints",
                            true);
  o.ids = LoadIds(record);
  return o;
}

Outcome SimServer::ApplyModelCommand(Command& cmd) {
  using K = Command::Kind;
  if (cmd.kind == K::kLoadModel) return LoadModel(cmd);
  if (cmd.kind == K::kModelInfo) {
    model_info_due_ = true;
    return Outcome::Done("model info on " + publisher_.Channel("MODEL_INFO"), false);
  }
  const ModelRecord* m = model::FindModel(world_, cmd.model_id);
  if (m == nullptr) return Outcome::Failed(Status::NotFound("unknown model id " + std::to_string(cmd.model_id)));
  for (const ModelLinkEntry& l : m->links) WakeTouching(world_, l.body);  // what rested on it
  ModelRecord removed;
  if (Status st = model::RemoveModel(cmd.model_id, &world_, &removed); !st.ok()) return Outcome::Failed(st);
  detector_.Reset();
  return Outcome::Done("removed model \"" + removed.name + "\" " + std::to_string(removed.id), true);
}

// A body or joint of a model leaves only with its model (docs/models.md).
Status SimServer::CheckNotInModel(BodyId body, JointId joint) const {
  for (const ModelRecord& m : world_.models) {
    for (const ModelLinkEntry& l : m.links) {
      if (body != 0 && l.body == body) {
        return Status::FailedPrecondition("body " + std::to_string(body) + " is link \"" + l.name + "\" of model \"" +
                                          m.name + "\" " + std::to_string(m.id) + "; remove the model as a whole");
      }
    }
    for (const ModelJointEntry& j : m.joints) {
      if (joint != 0 && j.joint == joint) {
        return Status::FailedPrecondition("joint " + std::to_string(joint) + " is joint \"" + j.name +
                                          "\" of model \"" + m.name + "\" " + std::to_string(m.id) +
                                          "; remove the model as a whole");
      }
    }
  }
  return Status::Ok();
}

void SimServer::PublishModelInfo() {
  // publish when the list changed (a load, a remove, a reset, a restore) or was asked for
  Fnv1a h;
  for (const ModelRecord& m : world_.models) {
    h.Bytes(&m.id, sizeof m.id);
    for (const ModelLinkEntry& l : m.links) h.Bytes(&l.body, sizeof l.body);
  }
  const uint64_t signature = h.h ^ world_.models.size();
  if (!model_info_due_ && signature == models_published_) return;
  publisher_.Publish(publisher_.Channel("MODEL_INFO"), MakeModelInfoMessage(world_));
  models_published_ = signature;
  model_info_due_ = false;
}

}  // namespace contactsim
