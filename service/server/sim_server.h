// The server's core, independent of LCM: the LCM thread hands it raw
// payloads of the command channels (OnMessage; command_channels.h), which
// are decoded and checked at once against the limits; good commands wait in
// a bounded inbox until the simulation thread (Run) applies them in arrival
// order at a step boundary. Only the simulation thread touches the world, so
// the engine needs no locks.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <contactsim/reply_t.hpp>

#include "service/collision/collision_detector.h"
#include "service/contact/contact_method.h"
#include "service/contact/sleep/island_sleep.h"
#include "service/physics/world.h"
#include "service/scene/scene_spec.h"
#include "service/server/command.h"
#include "service/server/command_auth.h"
#include "service/server/command_channels.h"
#include "service/server/journal.h"
#include "service/server/rate_limiter.h"
#include "service/server/server_options.h"
#include "service/server/snapshot_store.h"
#include "service/server/transport.h"

namespace contactsim {

// What applying one command did: the reply's status and text, the new ids,
// and whether the world's content changed.
struct Outcome {
  Status status;
  std::string message;       // the reply's text when the status is OK
  std::vector<int64_t> ids;  // ADD: the new id
  bool changed = false;      // the world's content changed
  bool deferred = false;     // answered later (STEP when its last step is done; an accepted input by its STATE)

  static Outcome Done(std::string message, bool changed) {
    Outcome o;
    o.message = std::move(message);
    o.changed = changed;
    return o;
  }
  static Outcome Failed(Status status) {
    Outcome o;
    o.status = std::move(status);
    return o;
  }
};

class SimServer {
 public:
  SimServer(ServerOptions options, Transport* transport);

  // Builds the initial world (a null scene gives an empty one) and method;
  // with a journal folder that holds a snapshot, recovers from it instead
  // (snapshot + the journal records after it).
  Status Init(const SceneSpec* scene, std::shared_ptr<ContactMethod> method);

  // LCM thread: one payload received on `channel`; a command channel's
  // payload is decoded, checked and queued or answered at once (anything
  // else is ignored). Never throws.
  void OnMessage(const std::string& channel, const void* data, int size);
  // The full names of the command channels, to subscribe to.
  std::vector<std::string> CommandChannelNames() const;

  // Simulation thread: runs until `stop` is set, then returns.
  void Run(const std::atomic<bool>& stop);
  // One turn of the loop without pacing, for tests: applies the inbox and,
  // unless paused with no STEP pending, takes one step. True if it stepped.
  bool Tick();

  // Re-simulation of a recorded run (log_replay.h) drives these instead of
  // Run: the commands given so far are applied now, and steps are taken
  // when the log says, without pacing or lockstep waits.
  void ApplyInbox() { DrainInbox(); }
  void StepOnce() { StepWorld(); }
  uint64_t input_digest() const { return input_digest_; }  // of the last step's inputs

  std::string Channel(const char* suffix) const { return options_.prefix + "_" + suffix; }
  const World& world() const { return world_; }
  const ContactMethod& method() const { return *method_; }
  bool paused() const { return paused_; }

 private:
  Status Enqueue(Command& cmd);
  Status AdmitClient(const CommandChannel& channel, const std::string& client_id);
  // journal, snapshots, rewind and recovery (snapshot_commands.cpp)
  Status Recover();
  proto::Snapshot SaveDurableSnapshot();
  void StartTimeline();
  void TakePeriodicSnapshot();
  Outcome ApplySnapshotCommand(Command& cmd);
  Status Rewind(int64_t step, const Command* cmd = nullptr);
  Status ReplayRecord(const JournalRecord& record);
  Status JournalCommand(RecordKind kind, const std::string& payload);
  void SimulateStep();
  // batches, replies and their undo (command_batch.cpp)
  bool DrainInbox();  // true if a command changed the world
  void ApplyFromInbox(Command& cmd, bool* changed);
  void CommitBatch();
  void UndoBatch(const Status& why);
  void PublishReply(const reply_t& reply);
  void FlushReplies();
  // lockstep (lockstep_commands.cpp)
  Outcome ApplyLockstepCommand(Command& cmd);
  bool LockstepReady(const std::atomic<bool>* stop);  // null: never blocks
  void ApplyInputs();
  void ApplyInput(const ControllerInput& input, bool live);

  void Reject(const std::string& client_id, int64_t request_id, const Status& status, const char* channel);
  void CountRejection(const Status& status);
  void SendReply(const std::string& client_id, int64_t request_id, const Status& status, const std::string& message,
                 const std::vector<int64_t>& ids = {});
  Outcome Apply(Command& cmd);
  Outcome ApplyBodyCommand(Command& cmd);   // bodies and joints (body_commands.cpp)
  Outcome ApplyToBody(Command& cmd, RigidBody* b);  // a command on one existing body
  Outcome ApplyWorldCommand(Command& cmd);  // scene, method, running (world_commands.cpp)
  RigidBody* FindBody(BodyId id, bool need_dynamic, Status* status);
  void StepWorld();
  void FinishStepCommands();
  void CancelStepCommands(const std::string& why);
  // progress of long commands on PROGRESS (progress_t), at most every
  // kProgressPeriod unless `now` is set (progress.cpp)
  void ReportStepProgress(bool now);
  void ReportRewindProgress();
  void PublishProgress(const std::string& client_id, int64_t request_id, const char* command, int64_t done,
                       int64_t total, std::chrono::steady_clock::time_point since);
  void UpdateRates();
  void PublishState();
  void PublishContacts();
  void PublishStatus(std::chrono::steady_clock::time_point now);
  void PrintLiveLine(bool final_line);

  ServerOptions options_;
  Transport* transport_;
  const Material default_material_{};

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Command> inbox_;
  std::atomic<int64_t> accepted_{0}, rejected_{0}, unauthenticated_{0}, limited_{0};
  std::string last_error_;  // guarded by mutex_

  // LCM thread only
  DecodeContext decode_context_;
  RateLimiter rate_limiter_;
  std::unique_ptr<CommandAuthenticator> auth_;  // null without a key

  // simulation thread only
  World world_;
  CollisionDetector detector_;
  std::shared_ptr<ContactMethod> method_;
  IslandSleep sleep_;
  ContactSet contacts_;
  StepStats last_stats_;
  bool paused_ = false;
  RunMode mode_ = RunMode::kRealtime;
  double real_time_factor_ = 1.0;
  bool reanchor_ = true;
  int64_t state_every_ = 1, contacts_every_ = 1;
  int64_t last_state_step_ = -1;
  struct PendingStep {
    std::string client_id;
    int64_t request_id;
    int64_t target_step;
    int64_t steps;  // asked for: the first is target_step - steps + 1
    std::chrono::steady_clock::time_point accepted;
  };
  std::deque<PendingStep> pending_steps_;
  std::chrono::steady_clock::time_point last_progress_{};
  struct Rewinding {  // a REWIND re-simulating, for its progress reports
    std::string client_id;
    int64_t request_id;
    int64_t from, to;  // steps
    std::chrono::steady_clock::time_point accepted, last;
  };
  std::optional<Rewinding> rewinding_;
  int64_t step_budget_ = 0;
  Journal journal_;
  SnapshotStore snapshots_;
  bool replaying_ = false;         // applying journal records: no replies, no journaling
  bool hold_replies_ = false;      // a batch is being applied: reply after the journal sync
  // Replies of the batch, sent once its journal records are durable; those
  // of journaled commands become INTERNAL if the batch is undone.
  struct HeldReply {
    reply_t reply;
    bool undoable;
  };
  std::vector<HeldReply> held_replies_;
  bool reply_undoable_ = false;    // the reply being sent is a journaled command's
  // The world before the batch's first journaled command, kept while a disk
  // journal may still refuse the batch (a failed write or sync undoes it).
  struct UndoPoint {
    World world;
    std::shared_ptr<ContactMethod> method;
    Journal::Mark mark;
  };
  std::optional<UndoPoint> undo_;
  Lockstep lockstep_;
  uint64_t input_digest_ = 0;      // of the inputs applied in the last step
  bool republish_state_ = false;   // a controller registered: it needs the current STATE
  bool lockstep_waiting_ = false;
  std::chrono::steady_clock::time_point lockstep_wait_start_;
  std::chrono::steady_clock::time_point lockstep_last_state_;  // last STATE sent while waiting

  // rates for STATUS and the live line
  std::chrono::steady_clock::time_point last_status_wall_;
  int64_t last_status_step_ = 0;
  double last_status_time_ = 0.0;
  double step_rate_ = 0.0, measured_rtf_ = 0.0;
  std::chrono::steady_clock::time_point last_live_line_;
};

}  // namespace contactsim
