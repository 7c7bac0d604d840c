#include "service/server/command_batch.h"

#include <spdlog/spdlog.h>

#include "service/server/messages.h"

namespace contactsim {
namespace {

// Commands whose effect the journal must carry to a replay: the ones that
// change the world without replacing it (reset, load and restore start a
// new timeline from a snapshot instead).
bool Journaled(Command::Kind kind) {
  using K = Command::Kind;
  switch (kind) {
    case K::kAddBody: case K::kRemoveBody: case K::kSetPose: case K::kSetVelocity: case K::kApplyForce:
    case K::kApplyImpulse: case K::kSetMass: case K::kSetMaterial: case K::kSetFilter: case K::kSetGravity:
    case K::kSetTimestep: case K::kSetMethod: case K::kAddJoint: case K::kRemoveJoint: case K::kAddRangeSensor:
    case K::kAddContactSensor: case K::kRemoveSensor: case K::kLoadModel: case K::kRemoveModel: case K::kArmCommand:
    case K::kWsgCommand: case K::kSetActuators: case K::kClearActuators:
      return true;
    default:
      return false;
  }
}

// Commands that replace the world or copy it: the batch so far is committed
// first, so that an undo never reaches across them.
bool EndsBatch(Command::Kind kind) {
  using K = Command::Kind;
  return kind == K::kReset || kind == K::kLoadScene || kind == K::kRestore || kind == K::kRewind ||
         kind == K::kSnapshot;
}

}  // namespace

CommandBatch::CommandBatch(const ServerOptions& options, const Publisher* publisher, const World* world,
                           const std::shared_ptr<ContactMethod>* method, Hooks hooks)
    : max_queued_(options.max_queued_commands),
      publisher_(publisher),
      world_(world),
      method_(method),
      hooks_(std::move(hooks)),
      history_(options.max_snapshots) {}

// ---- LCM thread -----------------------------------------------------------

Status CommandBatch::Enqueue(Command& cmd) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (static_cast<int>(inbox_.size()) >= max_queued_) {
      return Status::ResourceExhausted("the server's inbox holds max_queued_commands = " +
                                       std::to_string(max_queued_) + " commands; try again");
    }
    inbox_.push_back(std::move(cmd));
  }
  if (!hold_wake_ups_) wake_.notify_one();
  return Status::Ok();
}

void CommandBatch::Reject(const std::string& client_id, int64_t request_id, const Status& status, const char* channel) {
  CountRejection(status);
  spdlog::warn("rejected {} from \"{}\" #{}: {}", channel, client_id, request_id, status.message());
  reply_t r;
  r.client_id = client_id;
  r.request_id = request_id;
  r.code = static_cast<int32_t>(status.code());
  r.message = status.message();
  r.step = -1;
  r.time = 0.0;
  r.num_ids = 0;
  publisher_->Reply(r);
}

void CommandBatch::CountRejection(const Status& status) {
  ++rejected_;
  if (status.code() == StatusCode::kUnauthenticated) ++unauthenticated_;
  if (status.code() == StatusCode::kResourceExhausted) ++limited_;
  std::lock_guard<std::mutex> lock(mutex_);
  last_error_ = status.message();
}

// ---- simulation thread ----------------------------------------------------

void CommandBatch::Wait(std::chrono::steady_clock::time_point until, const std::atomic<bool>& stop) {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait_until(lock, until, [this, &stop] { return !inbox_.empty() || woken_ || stop.load(); });
  woken_ = false;
}

void CommandBatch::Wake() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    woken_ = true;
  }
  wake_.notify_one();
}

bool CommandBatch::Drain() {
  std::deque<Command> batch;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    batch.swap(inbox_);
  }
  bool changed = false;
  holding_ = true;
  for (Command& cmd : batch) ApplyFromInbox(cmd, &changed);
  Commit();
  holding_ = false;
  return changed;
}

void CommandBatch::ApplyFromInbox(Command& cmd, bool* changed) {
  const bool journaled = Journaled(cmd.kind);
  if (EndsBatch(cmd.kind)) Commit();
  if (journaled && journal_.open() && !undo_) undo_ = UndoPoint{*world_, *method_, journal_.mark()};
  Outcome out = hooks_.apply(cmd);
  if (out.status.ok() && journaled) {
    const Status st = Record(cmd.record, cmd.payload);
    if (!st.ok()) {
      Undo(st);  // this command too: it answers INTERNAL below
      out = Outcome::Failed(Status::Internal("not applied: " + st.message()));
    }
  }
  *changed |= out.changed && out.status.ok();
  if (out.deferred) return;
  reply_undoable_ = journaled && out.status.ok();
  SendReply(cmd.client_id, cmd.request_id, out.status, out.message, out.ids);
  reply_undoable_ = false;
}

void CommandBatch::Commit() {
  const Status st = journal_.Sync();
  if (!st.ok()) Undo(st);
  undo_.reset();
  for (const HeldReply& h : held_) PublishReply(h.reply);
  held_.clear();
}

void CommandBatch::Undo(const Status& why) {
  spdlog::error("{}; the batch's journaled commands are undone and answered INTERNAL", why.message());
  if (undo_) {
    hooks_.restore(std::move(undo_->world), std::move(undo_->method));
    const Status cut = journal_.RollBack(undo_->mark);
    if (!cut.ok()) spdlog::critical("{}", cut.message());
    history_.DropRecordsFrom(undo_->mark.seq);
    undo_.reset();
  }
  for (HeldReply& h : held_) {
    if (!h.undoable) continue;
    h.undoable = false;
    h.reply.code = static_cast<int32_t>(StatusCode::kInternal);
    h.reply.message = "not applied: " + why.message();
    h.reply.ids.clear();
    h.reply.num_ids = 0;
    --accepted_;
    CountRejection(Status::Internal(h.reply.message));
  }
}

void CommandBatch::SendReply(const std::string& client_id, int64_t request_id, const Status& status,
                             const std::string& message, const std::vector<int64_t>& ids) {
  if (replaying_) return;
  reply_t r = MakeReply(client_id, request_id, status, *world_);
  if (status.ok()) {
    r.message = message;
    ++accepted_;
  } else {
    CountRejection(status);
    spdlog::warn("rejected command from \"{}\" #{}: {}", client_id, request_id, status.message());
  }
  r.ids = ids;
  r.num_ids = static_cast<int32_t>(ids.size());
  if (holding_) {
    held_.push_back({std::move(r), reply_undoable_});
  } else {
    PublishReply(r);
  }
}

void CommandBatch::PublishReply(const reply_t& reply) {
  // nothing is acknowledged before its journal record is durable
  const Status st = journal_.Sync();
  if (!st.ok()) spdlog::error("{}", st.message());
  publisher_->Reply(reply);
}

Status CommandBatch::Record(RecordKind kind, const std::string& payload) {
  if (replaying_) return Status::Ok();
  JournalRecord record;
  const Status st = journal_.Append(kind, world_->step, payload, &record);
  if (!st.ok()) return st;
  history_.AddRecord(std::move(record));
  return Status::Ok();
}

void CommandBatch::CountInto(status_t* s) {
  s->commands_accepted = accepted_;
  s->commands_rejected = rejected_;
  s->commands_unauthenticated = unauthenticated_;
  s->commands_limited = limited_;
  std::lock_guard<std::mutex> lock(mutex_);
  s->last_error = last_error_;
}

}  // namespace contactsim
