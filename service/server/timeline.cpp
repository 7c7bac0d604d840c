// SimServer's timeline: the snapshot that REWIND and crash recovery start
// from, periodic snapshots, recovery from the journal folder and the
// re-simulation of REWIND (docs/snapshots.md). The journal and the history
// of records are the batch's (command_batch.h). Simulation thread.
#include <spdlog/spdlog.h>

#include <climits>

#include "service/scene/snapshot.h"
#include "service/scene/snapshot_manifolds.h"
#include "service/server/arm_driver/driver_commands.h"
#include "service/server/sim_server.h"

namespace contactsim {

// The current world as a snapshot that the journal continues from, written
// to the journal folder when there is one.
proto::Snapshot SimServer::SaveDurableSnapshot() {
  proto::Snapshot s = SaveState();
  Journal& journal = batch_.journal();
  s.set_journal_seq(journal.next_seq());
  if (journal.open()) {
    Status st = journal.WriteSnapshot(s);
    if (!st.ok()) spdlog::error("{}", st.message());
  }
  return s;
}

// The world was replaced (start, reset, scene load, restore, recovery): the
// current state becomes the base that REWIND and crash recovery start from.
void SimServer::StartTimeline() { batch_.history().StartTimeline(SaveDurableSnapshot()); }

void SimServer::TakePeriodicSnapshot() {
  if (!batch_.replaying()) batch_.history().AddPeriodic(SaveDurableSnapshot());
}

namespace {

// Records were accepted under the limits of their day: a replay applies
// them whatever the limits are now.
const DecodeContext& RecordContext() {
  static const DecodeContext context = [] {
    DecodeContext c;
    c.limits = {INT_MAX, INT_MAX, INT_MAX, INT_MAX, INT_MAX};
    c.limits.max_model_cmd_bytes = INT_MAX;  // a journaled LOAD was admitted once already
    c.limits.max_model_text_bytes = INT_MAX;
    c.limits.max_actuator_cmd_bytes = INT_MAX;
    return c;
  }();
  return context;
}

}  // namespace

Status SimServer::ReplayRecord(const JournalRecord& r) {
  if (r.step < world_.step) {
    return Status::FailedPrecondition("journal record " + std::to_string(r.seq) + " applies at step " +
                                      std::to_string(r.step) + ", but the world is at step " +
                                      std::to_string(world_.step));
  }
  while (world_.step < r.step) SimulateStep();
  if (r.kind == RecordKind::kStepTo) return Status::Ok();
  const CommandChannel* channel = ChannelOfRecord(r.kind);
  Command cmd;
  Status st = Status::DecodeError("unknown record kind");
  if (channel != nullptr) {
    st = channel->decode(r.payload.data(), static_cast<int>(r.payload.size()), RecordContext(), &cmd);
  } else if (r.kind == RecordKind::kArmCommand || r.kind == RecordKind::kWsgCommand) {
    // the drivers' channels are the config's, not the table's
    int64_t utime = 0;
    st = DecodeDriverCommand(r.kind, arm_ ? arm_->protocol() : nullptr, r.payload.data(),
                             static_cast<int>(r.payload.size()), &cmd, &utime);
  }
  if (st.ok() && cmd.kind == Command::Kind::kInput) {
    ApplyInput(cmd.input, false);
  } else if (st.ok() && !(st = Apply(cmd).status).ok()) {
    st = Status::FailedPrecondition("no longer applies: " + st.message());
  }
  if (!st.ok()) return Status::FailedPrecondition("journal record " + std::to_string(r.seq) + ": " + st.message());
  return Status::Ok();
}

Status SimServer::Recover() {
  if (options_.journal_dir.empty()) {
    StartTimeline();
    return Status::Ok();
  }
  Journal& journal = batch_.journal();
  Status st = journal.Open(options_.journal_dir, options_.journal_fsync);
  if (!st.ok()) return st;
  if (journal.recovered_snapshot()) {
    World world;
    std::shared_ptr<ContactMethod> method;
    std::vector<CachedManifold> manifolds;
    st = LoadSnapshot(*journal.recovered_snapshot(), &world, &method);
    if (st.ok()) st = ReadManifolds(*journal.recovered_snapshot(), &manifolds);
    if (!st.ok()) return Status::FailedPrecondition(options_.journal_dir + ": " + st.message());
    ReplaceWorld(std::move(world), std::move(method), std::move(manifolds));
    const int64_t from_step = world_.step;
    batch_.set_replaying(true);
    for (const JournalRecord& r : journal.recovered_records()) {
      if (!(st = ReplayRecord(r)).ok()) break;
    }
    RestoreStandingActuators();  // a last input whose step was not taken; its controller sends it again
    batch_.set_replaying(false);
    if (!st.ok()) return Status::FailedPrecondition(options_.journal_dir + ": " + st.message());
    spdlog::info("recovered from {}: snapshot at step {} + {} journal records -> step {}, {} bodies",
                 options_.journal_dir, from_step, journal.recovered_records().size(), world_.step,
                 world_.bodies().size());
  }
  journal.DropRecovered();
  StartTimeline();
  return Status::Ok();
}

Status SimServer::Rewind(int64_t step, const Command* cmd) {
  SnapshotStore::Plan plan;
  Status st = batch_.history().PlanRewind(step, world_.step, &plan);
  if (!st.ok()) return st;
  World world;
  std::shared_ptr<ContactMethod> method;
  std::vector<CachedManifold> manifolds;
  if (!(st = LoadSnapshot(*plan.from, &world, &method)).ok()) return st;
  if (!(st = ReadManifolds(*plan.from, &manifolds)).ok()) return st;
  // replay on the live members, restoring them if the journal fails
  World saved_world = std::move(world_);
  std::shared_ptr<ContactMethod> saved_method = std::move(method_);
  std::vector<CachedManifold> saved_manifolds = detector_.manifolds().entries();
  ReplaceWorld(std::move(world), std::move(method), std::move(manifolds));
  batch_.set_replaying(true);
  if (cmd != nullptr) steps_.BeginRewind(*cmd, world_.step, step);
  for (const JournalRecord* r : plan.records) {
    if (!(st = ReplayRecord(*r)).ok()) break;
  }
  while (st.ok() && world_.step < step) SimulateStep();
  RestoreStandingActuators();  // an input recorded for the step after `step` is not taken
  batch_.set_replaying(false);
  steps_.EndRewind();
  if (!st.ok()) {
    ReplaceWorld(std::move(saved_world), std::move(saved_method), std::move(saved_manifolds));
    return st;
  }
  batch_.history().TruncateAfter(step);
  // what the disk journal holds after `step` is no longer this run's future
  if (batch_.journal().open()) SaveDurableSnapshot();
  return Status::Ok();
}

}  // namespace contactsim
