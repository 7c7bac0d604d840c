// SimServer's command batches: the inbox is applied at a step boundary,
// each command's journal record is written, and the replies go out once
// the batch's records are durable (a group commit). When the disk journal
// refuses a record or the sync, the batch's journaled commands are undone
// (the world as it was before the first of them, the journal cut back) and
// answered INTERNAL: nothing is acknowledged that a restart would lose, and
// nothing is applied that was not acknowledged (docs/reliability.md).
// Simulation thread.
#include <spdlog/spdlog.h>

#include "service/server/messages.h"
#include "service/server/sim_server.h"

namespace contactsim {
namespace {

// Commands whose effect the journal must carry to a replay: the ones that
// change the world without replacing it (reset, load and restore start a
// new timeline from a snapshot instead).
bool Journaled(Command::Kind kind) {
  using K = Command::Kind;
  switch (kind) {
    case K::kAddBody: case K::kRemoveBody: case K::kSetPose: case K::kSetVelocity: case K::kApplyForce:
    case K::kApplyImpulse: case K::kSetMass: case K::kSetMaterial: case K::kSetGravity: case K::kSetTimestep:
    case K::kSetMethod: case K::kAddJoint: case K::kRemoveJoint:
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

Outcome SimServer::Apply(Command& cmd) {
  using K = Command::Kind;
  switch (cmd.kind) {
    case K::kAddBody: case K::kRemoveBody: case K::kSetPose: case K::kSetVelocity: case K::kApplyForce:
    case K::kApplyImpulse: case K::kSetMass: case K::kSetMaterial: case K::kAddJoint: case K::kRemoveJoint:
      return ApplyBodyCommand(cmd);
    case K::kSnapshot: case K::kRestore: case K::kRewind:
      return ApplySnapshotCommand(cmd);
    case K::kRegisterController: case K::kReleaseController: case K::kInput:
      return ApplyLockstepCommand(cmd);
    default:
      return ApplyWorldCommand(cmd);
  }
}

bool SimServer::DrainInbox() {
  std::deque<Command> batch;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    batch.swap(inbox_);
  }
  bool changed = false;
  hold_replies_ = true;
  for (Command& cmd : batch) ApplyFromInbox(cmd, &changed);
  CommitBatch();
  hold_replies_ = false;
  return changed;
}

void SimServer::ApplyFromInbox(Command& cmd, bool* changed) {
  const bool journaled = Journaled(cmd.kind);
  if (EndsBatch(cmd.kind)) CommitBatch();
  if (journaled && journal_.open() && !undo_) undo_ = UndoPoint{world_, method_, journal_.mark()};
  Outcome out = Apply(cmd);
  if (out.status.ok() && journaled) {
    const Status st = JournalCommand(cmd.record, cmd.payload);
    if (!st.ok()) {
      UndoBatch(st);  // this command too: it answers INTERNAL below
      out = Outcome::Failed(Status::Internal("not applied: " + st.message()));
    }
  }
  *changed |= out.changed && out.status.ok();
  if (out.deferred) return;
  reply_undoable_ = journaled && out.status.ok();
  SendReply(cmd.client_id, cmd.request_id, out.status, out.message, out.ids);
  reply_undoable_ = false;
}

// The batch's records are made durable, then its replies go out; a failed
// sync undoes the batch first.
void SimServer::CommitBatch() {
  const Status st = journal_.Sync();
  if (!st.ok()) UndoBatch(st);
  undo_.reset();
  FlushReplies();
}

void SimServer::UndoBatch(const Status& why) {
  spdlog::error("{}; the batch's journaled commands are undone and answered INTERNAL", why.message());
  if (undo_) {
    world_ = std::move(undo_->world);
    method_ = std::move(undo_->method);
    detector_.Reset();
    sleep_.Reset();
    contacts_.clear();
    UpdateRates();
    const Status cut = journal_.RollBack(undo_->mark);
    if (!cut.ok()) spdlog::critical("{}", cut.message());
    snapshots_.DropRecordsFrom(undo_->mark.seq);
    undo_.reset();
  }
  for (HeldReply& h : held_replies_) {
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

void SimServer::SendReply(const std::string& client_id, int64_t request_id, const Status& status,
                          const std::string& message, const std::vector<int64_t>& ids) {
  if (replaying_) return;
  reply_t r = MakeReply(client_id, request_id, status, world_);
  if (status.ok()) {
    r.message = message;
    ++accepted_;
  } else {
    CountRejection(status);
    spdlog::warn("rejected command from \"{}\" #{}: {}", client_id, request_id, status.message());
  }
  r.ids = ids;
  r.num_ids = static_cast<int32_t>(ids.size());
  if (hold_replies_) {
    held_replies_.push_back({std::move(r), reply_undoable_});
  } else {
    PublishReply(r);
  }
}

void SimServer::PublishReply(const reply_t& reply) {
  // nothing is acknowledged before its journal record is durable
  const Status st = journal_.Sync();
  if (!st.ok()) spdlog::error("{}", st.message());
  const int n = reply.getEncodedSize();
  std::vector<uint8_t> buf(n);
  reply.encode(buf.data(), 0, n);
  transport_->Publish(Channel("REPLY"), buf.data(), n);
}

void SimServer::FlushReplies() {
  for (const HeldReply& h : held_replies_) PublishReply(h.reply);
  held_replies_.clear();
}

Status SimServer::JournalCommand(RecordKind kind, const std::string& payload) {
  if (replaying_) return Status::Ok();
  JournalRecord record;
  const Status st = journal_.Append(kind, world_.step, payload, &record);
  if (!st.ok()) return st;
  snapshots_.AddRecord(std::move(record));
  return Status::Ok();
}

}  // namespace contactsim
