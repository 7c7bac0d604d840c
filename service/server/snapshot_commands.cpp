// SimServer's journal, snapshot, rewind and recovery handling (the rest of
// the class is in sim_server.cpp). Everything here runs on the simulation
// thread.
#include <spdlog/spdlog.h>

#include <climits>

#include "service/scene/snapshot.h"
#include "service/server/sim_server.h"

namespace contactsim {

// The current world as a snapshot that the journal continues from, written
// to the journal folder when there is one.
proto::Snapshot SimServer::SaveDurableSnapshot() {
  proto::Snapshot s;
  SaveSnapshot(world_, *method_, &s);
  s.set_journal_seq(journal_.next_seq());
  if (journal_.open()) {
    Status st = journal_.WriteSnapshot(s);
    if (!st.ok()) spdlog::error("{}", st.message());
  }
  return s;
}

// The world was replaced (start, reset, scene load, restore, recovery): the
// current state becomes the base that REWIND and crash recovery start from.
void SimServer::StartTimeline() { snapshots_.StartTimeline(SaveDurableSnapshot()); }

void SimServer::TakePeriodicSnapshot() {
  if (!replaying_) snapshots_.AddPeriodic(SaveDurableSnapshot());
}

namespace {

// Records were accepted under the limits of their day: a replay applies
// them whatever the limits are now.
const DecodeContext& RecordContext() {
  static const DecodeContext context = [] {
    DecodeContext c;
    c.limits = {INT_MAX, INT_MAX, INT_MAX, INT_MAX, INT_MAX};
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
  Status st = channel == nullptr ? Status::DecodeError("unknown record kind")
                                 : channel->decode(r.payload.data(), static_cast<int>(r.payload.size()),
                                                   RecordContext(), &cmd);
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
  Status st = journal_.Open(options_.journal_dir, options_.journal_fsync);
  if (!st.ok()) return st;
  if (journal_.recovered_snapshot()) {
    World world;
    std::shared_ptr<ContactMethod> method;
    if (!(st = LoadSnapshot(*journal_.recovered_snapshot(), &world, &method)).ok()) {
      return Status::FailedPrecondition(options_.journal_dir + ": " + st.message());
    }
    world_ = std::move(world);
    method_ = std::move(method);
    detector_.Reset();
    sleep_.Reset();
    const int64_t from_step = world_.step;
    replaying_ = true;
    for (const JournalRecord& r : journal_.recovered_records()) {
      if (!(st = ReplayRecord(r)).ok()) break;
    }
    replaying_ = false;
    if (!st.ok()) return Status::FailedPrecondition(options_.journal_dir + ": " + st.message());
    spdlog::info("recovered from {}: snapshot at step {} + {} journal records -> step {}, {} bodies",
                 options_.journal_dir, from_step, journal_.recovered_records().size(), world_.step,
                 world_.bodies().size());
  }
  journal_.DropRecovered();
  StartTimeline();
  return Status::Ok();
}

Status SimServer::Rewind(int64_t step, const Command* cmd) {
  SnapshotStore::Plan plan;
  Status st = snapshots_.PlanRewind(step, world_.step, &plan);
  if (!st.ok()) return st;
  World world;
  std::shared_ptr<ContactMethod> method;
  if (!(st = LoadSnapshot(*plan.from, &world, &method)).ok()) return st;
  // replay on the live members, restoring them if the journal fails
  World saved_world = std::move(world_);
  std::shared_ptr<ContactMethod> saved_method = std::move(method_);
  world_ = std::move(world);
  method_ = std::move(method);
  detector_.Reset();
  sleep_.Reset();
  replaying_ = true;
  if (cmd != nullptr) {
    const auto now = std::chrono::steady_clock::now();
    rewinding_ = Rewinding{cmd->client_id, cmd->request_id, world_.step, step, now, now};
    PublishProgress(cmd->client_id, cmd->request_id, "REWIND", 0, step - world_.step, now);
  }
  for (const JournalRecord* r : plan.records) {
    if (!(st = ReplayRecord(*r)).ok()) break;
  }
  while (st.ok() && world_.step < step) SimulateStep();
  replaying_ = false;
  rewinding_.reset();
  if (!st.ok()) {
    world_ = std::move(saved_world);
    method_ = std::move(saved_method);
    detector_.Reset();
    sleep_.Reset();
    return st;
  }
  snapshots_.TruncateAfter(step);
  // what the disk journal holds after `step` is no longer this run's future
  if (journal_.open()) SaveDurableSnapshot();
  return Status::Ok();
}

Outcome SimServer::ApplySnapshotCommand(Command& cmd) {
  using K = Command::Kind;
  const std::string target = cmd.snapshot_name.empty() ? "file " + cmd.snapshot_path : "\"" + cmd.snapshot_name + "\"";
  Status st;
  if (cmd.kind == K::kSnapshot) {
    proto::Snapshot s;
    SaveSnapshot(world_, *method_, &s);
    s.set_journal_seq(journal_.next_seq());
    if (!cmd.snapshot_path.empty()) {
      // a replay must not overwrite the recorded run's file (a RESTORE from it comes later)
      if (options_.write_files) st = WriteSnapshotFile(cmd.snapshot_path, s, options_.journal_fsync == FsyncPolicy::kAlways);
    } else {
      snapshots_.Put(cmd.snapshot_name, std::move(s));
    }
    if (!st.ok()) return Outcome::Failed(st);
    return Outcome::Done("snapshot " + target + " at step " + std::to_string(world_.step), false);
  }
  if (cmd.kind == K::kRewind) {
    const int64_t from = world_.step;
    st = Rewind(cmd.target_step, &cmd);
    if (!st.ok()) return Outcome::Failed(st);
    CancelStepCommands("rewind");
    return Outcome::Done("rewound from step " + std::to_string(from) + " to step " + std::to_string(world_.step), true);
  }
  proto::Snapshot loaded;
  const proto::Snapshot* s = nullptr;
  if (!cmd.snapshot_path.empty()) {
    st = ReadSnapshotFile(cmd.snapshot_path, &loaded);
    s = &loaded;
  } else if ((s = snapshots_.Find(cmd.snapshot_name)) == nullptr) {
    st = Status::NotFound("no snapshot named \"" + cmd.snapshot_name + "\"");
  }
  World world;
  std::shared_ptr<ContactMethod> method;
  if (st.ok()) st = LoadSnapshot(*s, &world, &method);
  if (!st.ok()) return Outcome::Failed(st);
  CancelStepCommands("restore");
  world_ = std::move(world);
  method_ = std::move(method);
  detector_.Reset();
  sleep_.Reset();
  contacts_.clear();
  UpdateRates();
  StartTimeline();
  return Outcome::Done("restored " + target + " at step " + std::to_string(world_.step), true);
}

}  // namespace contactsim
