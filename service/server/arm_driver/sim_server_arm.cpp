// SimServer's side of Drake's arm driver (arm_driver.h), and the start it
// shares with the WSG driver's (sim_server_wsg.cpp): the model loaded and
// held at start (a model the world does not hold yet may come later by
// MODEL_CMD; it is not held then), the commands applied at a step boundary
// like every other command (journaled, so recovery and REWIND replay them),
// and the status published at the driver's rate of simulated time.
#include <spdlog/spdlog.h>

#include "service/scene/scene_models.h"
#include "service/server/sim_server.h"

namespace contactsim {

Status SimServer::StartDriverModel(const char* block, const std::string& model,
                                   const std::optional<proto::SceneModel>& load, bool* present) {
  if (!options_.auth_key.empty()) {
    return Status::FailedPrecondition(std::string(block) + ": Drake's driver messages carry no signature, so a "
                                      "server with an auth key cannot accept them; remove auth_key_file or " + block);
  }
  *present = false;
  for (const ModelRecord& m : world_.models) *present |= m.name == model;
  if (load && !*present) {
    SceneModel scene_model;
    const model::ModelPaths paths =
        model::MakeModelPaths(options_.model_path_flags, options_.model_paths, model::ModelPathEnvironment());
    Status st = ReadSceneModel(*load, paths, std::string(block) + ": load", &scene_model);
    if (st.ok()) st = AddSceneModels({scene_model}, Material{}, &world_);
    if (!st.ok()) return st;
    *present = true;
  }
  if (!*present) {
    spdlog::warn("{}: the world holds no model named \"{}\" yet; its commands are refused and no status is "
                 "published until a MODEL_CMD LOAD brings it",
                 block, model);
  }
  return Status::Ok();
}

Status SimServer::StartArmDriver() {
  if (!arm_) return Status::Ok();
  const ArmDriverConfig& c = arm_->config();
  if (arm_->protocol() == nullptr) {
    return Status::InvalidArgument("arm_driver: protocol must be " + ArmProtocolNames() + ", got \"" + c.protocol +
                                   "\"");
  }
  bool present = false;
  Status st = StartDriverModel("arm_driver", c.model, c.load, &present);
  if (!st.ok()) return st;
  if (present && !(st = arm_->Hold(&world_)).ok()) return st.Prefixed("arm_driver: ");
  spdlog::info("arm driver: model \"{}\" on {} ({}) and {} ({} at {} Hz of simulated time)", c.model,
               c.command_channel, arm_->protocol()->command_type, c.status_channel, arm_->protocol()->status_type,
               c.status_rate_hz);
  return Status::Ok();
}

// Answered on REPLY, named by the channel and the command's utime: a
// refused one with the reason (logged and counted in STATUS's last_error,
// as a refused lockstep INPUT is), an accepted one with the step it applied
// at, which places it in an lcm-logger log for --replay (log_replay.h).
// Drake's own systems read no reply.
Outcome SimServer::ApplyArmCommand(Command& cmd) {
  if (!arm_) return Outcome::Failed(Status::FailedPrecondition("this server has no arm driver"));
  const Status st = arm_->Apply(cmd.arm, &world_);
  if (!st.ok()) return Outcome::Failed(st);
  return Outcome::Done("arm command applied", true);
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
