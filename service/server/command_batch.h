// The commands on their way from the LCM thread to the world: the bounded
// inbox, and each batch's application at a step boundary in arrival order
// with its journal records, group commit, undo and held replies. A reply
// goes out once the batch's records are durable; when the disk journal
// refuses a record or the sync, the batch's journaled commands are undone
// (the world as it was before the first of them, the journal cut back) and
// answered INTERNAL: nothing is acknowledged that a restart would lose, and
// nothing is applied that was not acknowledged (docs/reliability.md).
//
// The LCM thread calls Enqueue and Reject; everything else belongs to the
// thread that holds the loop's turn (the simulation thread, or the LCM
// thread while the simulation thread waits for lockstep inputs: sim_server.h).
// They share the inbox and the counters.
#pragma once

#include <contactsim/reply_t.hpp>
#include <contactsim/status_t.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/physics/world.h"
#include "service/server/command.h"
#include "service/server/journal.h"
#include "service/server/outcome.h"
#include "service/server/publisher.h"
#include "service/server/server_options.h"
#include "service/server/snapshot_store.h"

namespace contactsim {

class CommandBatch {
 public:
  // What the batch asks of the world's owner.
  struct Hooks {
    std::function<Outcome(Command&)> apply;  // one command on the world
    // the world and method from before the batch, back in place
    std::function<void(World&& world, std::shared_ptr<ContactMethod>&& method)> restore;
  };

  // `world` and `method` are the owner's, read for replies and undo copies.
  CommandBatch(const ServerOptions& options, const Publisher* publisher, const World* world,
               const std::shared_ptr<ContactMethod>* method, Hooks hooks);

  // LCM thread: moves `cmd` into the inbox, or leaves it when the inbox is
  // full; wakes a Wait unless wake-ups are held.
  Status Enqueue(Command& cmd);
  // LCM thread: while held, Enqueue wakes nobody (this thread drains the
  // inbox itself: SimServer's turn on the input's thread).
  void HoldWakeUps(bool hold) { hold_wake_ups_ = hold; }
  // LCM thread: an answer before the command reaches the world (no step).
  void Reject(const std::string& client_id, int64_t request_id, const Status& status, const char* channel);

  // Applies the inbox; true if a command changed the world.
  bool Drain();
  // Makes the records so far durable and sends the held replies; a
  // command that replaces the world commits first, so that no undo
  // reaches across it.
  void Commit();
  // Waits until a command arrives, Wake, `until`, or `stop`.
  void Wait(std::chrono::steady_clock::time_point until, const std::atomic<bool>& stop);
  // Ends the current or next Wait early.
  void Wake();

  // A reply to a command, held while a batch is applied.
  void SendReply(const std::string& client_id, int64_t request_id, const Status& status, const std::string& message,
                 const std::vector<int64_t>& ids = {});
  // A record of the journal at the world's step, kept in the history for REWIND.
  Status Record(RecordKind kind, const std::string& payload);

  // Applying recorded commands (recovery, REWIND): no replies, no records.
  void set_replaying(bool replaying) { replaying_ = replaying; }
  bool replaying() const { return replaying_; }
  Journal& journal() { return journal_; }
  SnapshotStore& history() { return history_; }
  // STATUS's command counters and last error.
  void CountInto(status_t* s);

 private:
  void ApplyFromInbox(Command& cmd, bool* changed);
  void Undo(const Status& why);
  void CountRejection(const Status& status);
  void PublishReply(const reply_t& reply);

  const int max_queued_;
  const Publisher* publisher_;
  const World* world_;
  const std::shared_ptr<ContactMethod>* method_;
  Hooks hooks_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Command> inbox_;
  bool woken_ = false;  // guarded by mutex_: Wake was called
  bool hold_wake_ups_ = false;  // LCM thread only
  std::atomic<int64_t> accepted_{0}, rejected_{0}, unauthenticated_{0}, limited_{0};
  std::string last_error_;  // guarded by mutex_

  // the turn's thread only
  Journal journal_;
  SnapshotStore history_;
  bool replaying_ = false;
  bool holding_ = false;  // a batch is being applied: reply after the journal sync
  // Replies of the batch; those of journaled commands become INTERNAL if it is undone.
  struct HeldReply {
    reply_t reply;
    bool undoable;
  };
  std::vector<HeldReply> held_;
  bool reply_undoable_ = false;  // the reply being sent is a journaled command's
  // The world before the batch's first journaled command, kept while a disk
  // journal may still refuse the batch.
  struct UndoPoint {
    World world;
    std::shared_ptr<ContactMethod> method;
    Journal::Mark mark;
  };
  std::optional<UndoPoint> undo_;
};

}  // namespace contactsim
