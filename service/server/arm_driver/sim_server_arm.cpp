// SimServer's side of Drake's arm driver (arm_driver.h): the model loaded
// and held at start (a model the world does not hold yet may come later by
// MODEL_CMD; it is not held then), the commands applied at a step boundary like every
// other command (journaled, so recovery and REWIND replay them), and the
// status published at the driver's rate of simulated time.
#include <spdlog/spdlog.h>

#include "service/scene/scene_models.h"
#include "service/server/sim_server.h"

namespace contactsim {

Status SimServer::StartArmDriver() {
  if (!arm_) return Status::Ok();
  const ArmDriverConfig& c = arm_->config();
  if (arm_->protocol() == nullptr) {
    return Status::InvalidArgument("arm_driver: protocol must be " + ArmProtocolNames() + ", got \"" + c.protocol +
                                   "\"");
  }
  if (!options_.auth_key.empty()) {
    return Status::FailedPrecondition("arm_driver: Drake's arm-driver messages carry no signature, so a server "
                                      "with an auth key cannot accept them; remove auth_key_file or arm_driver");
  }
  bool loaded = false;
  for (const ModelRecord& m : world_.models) loaded |= m.name == c.model;
  if (c.load && !loaded) {
    SceneModel model;
    const model::ModelPaths paths =
        model::MakeModelPaths(options_.model_path_flags, options_.model_paths, model::ModelPathEnvironment());
    Status st = ReadSceneModel(*c.load, paths, "arm_driver: load", &model);
    if (st.ok()) st = AddSceneModels({model}, Material{}, &world_);
    if (!st.ok()) return st;
  }
  if (c.load || loaded) {
    const Status st = arm_->Hold(&world_);
    if (!st.ok()) return st.Prefixed("arm_driver: ");
  } else {
    spdlog::warn("arm driver: the world holds no model named \"{}\" yet; its commands are refused and no status is "
                 "published until a MODEL_CMD LOAD brings it",
                 c.model);
  }
  spdlog::info("arm driver: model \"{}\" on {} ({}) and {} ({} at {} Hz of simulated time)", c.model,
               c.command_channel, arm_->protocol()->command_type, c.status_channel, arm_->protocol()->status_type,
               c.status_rate_hz);
  return Status::Ok();
}

// An accepted command is not answered, as Drake's driver answers none; a
// refused one is answered on REPLY (named by the channel and its utime),
// logged and counted in STATUS's last_error, as a refused lockstep INPUT is.
Outcome SimServer::ApplyArmCommand(Command& cmd) {
  if (!arm_) return Outcome::Failed(Status::FailedPrecondition("this server has no arm driver"));
  const Status st = arm_->Apply(cmd.arm, &world_);
  if (!st.ok()) return Outcome::Failed(st);
  Outcome out = Outcome::Done("", true);
  out.deferred = true;
  return out;
}

void SimServer::PublishArmStatus() {
  if (!arm_ || !arm_->StatusDue(world_.time)) return;
  ArmJointReadings readings;
  Status st = arm_->Read(world_, contacts_, method_->ValueKind(), &readings);
  if (st.ok()) st = arm_->protocol()->publish_status(publisher_, arm_->config().status_channel, world_.time, readings);
  if (!st.ok()) {
    spdlog::debug("arm driver: no status at t = {:.3f} s: {}", world_.time, st.message());
  }
}

}  // namespace contactsim
