// SimServer's side of Drake's Schunk WSG driver (wsg_driver.h), as the arm
// driver's (sim_server_arm.cpp): the model loaded and its fingers held at
// start, the commands applied at a step boundary and journaled as records
// of their own kind (RecordKind::kWsgCommand), the status published at the
// driver's rate of simulated time.
#include <spdlog/spdlog.h>

#include "service/server/sim_server.h"

namespace contactsim {

Status SimServer::StartWsgDriver() {
  if (!wsg_) return Status::Ok();
  const WsgDriverConfig& c = wsg_->config();
  bool present = false;
  Status st = StartDriverModel("wsg_driver", c.model, c.load, &present);
  if (!st.ok()) return st;
  if (present && !(st = wsg_->Hold(&world_)).ok()) return st.Prefixed("wsg_driver: ");
  spdlog::info("WSG driver: fingers \"{}\" and \"{}\" of model \"{}\" on {} (lcmt_schunk_wsg_command) and {} "
               "(lcmt_schunk_wsg_status at {} Hz of simulated time)",
               c.finger_joints[0], c.finger_joints[1], c.model, c.command_channel, c.status_channel, c.status_rate_hz);
  return Status::Ok();
}

// Answered as the arm driver's commands are (sim_server_arm.cpp): on
// REPLY, named by the channel and its utime, with the reason or the step
// it applied at.
Outcome SimServer::ApplyWsgCommand(Command& cmd) {
  if (!wsg_) return Outcome::Failed(Status::FailedPrecondition("this server has no WSG driver"));
  const Status st = wsg_->Apply(cmd.wsg, &world_);
  if (!st.ok()) return Outcome::Failed(st);
  return Outcome::Done("WSG command applied", true);
}

void SimServer::PublishWsgStatus() {
  if (!wsg_ || !wsg_->StatusDue(world_.time)) return;
  WsgReading reading;
  drake::lcmt_schunk_wsg_status m;
  Status st = wsg_->Read(world_, &reading);
  if (st.ok()) st = BuildWsgStatus(world_.time, reading, &m);
  if (st.ok()) {
    publisher_.Publish(wsg_->config().status_channel, m);
  } else {
    spdlog::debug("WSG driver: no status at t = {:.3f} s: {}", world_.time, st.message());
  }
}

}  // namespace contactsim
