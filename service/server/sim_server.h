// The server's core, independent of LCM: the LCM thread hands it raw command
// payloads (OnBodyMessage, OnSceneMessage, OnJointMessage), which are decoded and checked at
// once; good commands wait in an inbox until the simulation thread (Run)
// applies them in arrival order at a step boundary. Only the simulation
// thread touches the world, so the engine needs no locks.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "service/collision/collision_detector.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"
#include "service/scene/scene_spec.h"
#include "service/server/command.h"
#include "service/server/journal.h"
#include "service/server/snapshot_store.h"
#include "service/server/transport.h"

namespace contactsim {

struct ServerOptions {
  std::string prefix = "CONTACTSIM";    // channel prefix
  RunMode mode = RunMode::kRealtime;
  double real_time_factor = 1.0;        // sim s per wall s, REALTIME
  bool start_paused = false;
  double state_rate_hz = 60.0;          // of simulated time; 0 = every step
  double contacts_rate_hz = 30.0;       // of simulated time; 0 = every step
  double status_rate_hz = 1.0;          // of wall-clock time
  std::string broadphase = "sap";
  int max_bodies = 100000;
  bool live_line = false;               // progress line on stderr
  std::string journal_dir;              // "" = no journal on disk (REWIND still works)
  FsyncPolicy journal_fsync = FsyncPolicy::kAlways;
  int64_t snapshot_every = 0;           // steps between periodic snapshots; 0 = none
  int max_snapshots = 32;               // periodic snapshots kept in memory for REWIND
  LatePolicy late_policy = LatePolicy::kWait;  // for controllers registered without one
  double late_timeout = 0.1;            // s of wall-clock time, likewise
  bool write_files = true;              // false (a replay): SNAPSHOT to a file writes nothing
};

// Commands larger than this are refused before decoding.
constexpr int kMaxCommandBytes = 16 << 20;

class SimServer {
 public:
  SimServer(ServerOptions options, Transport* transport);

  // Builds the initial world (a null scene gives an empty one) and method;
  // with a journal folder that holds a snapshot, recovers from it instead
  // (snapshot + the journal records after it).
  Status Init(const SceneSpec* scene, std::shared_ptr<ContactMethod> method);

  // LCM thread.
  void OnBodyMessage(const void* data, int size);
  void OnSceneMessage(const void* data, int size);
  void OnInputMessage(const void* data, int size);  // input_t, lockstep
  void OnJointMessage(const void* data, int size);

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
  template <typename Msg, typename Decode>
  void Receive(const void* data, int size, const char* suffix, Decode decode);
  void Enqueue(Command cmd);
  // journal, snapshots, rewind and recovery (snapshot_commands.cpp)
  Status Recover();
  proto::Snapshot SaveDurableSnapshot();
  void StartTimeline();
  void TakePeriodicSnapshot();
  void ApplySnapshotCommand(Command& cmd);
  Status Rewind(int64_t step);
  Status ReplayRecord(const JournalRecord& record);
  void JournalCommand(RecordKind kind, const std::string& payload);
  void SimulateStep();
  void PublishReply(const std::vector<uint8_t>& bytes);
  void FlushReplies();
  // lockstep (lockstep_commands.cpp)
  void ApplyLockstepCommand(Command& cmd);
  bool LockstepReady(const std::atomic<bool>* stop);  // null: never blocks
  void ApplyInputs();
  void ApplyInput(const ControllerInput& input, bool live);

  void Reject(const std::string& client_id, int64_t request_id, int32_t code, const std::string& message,
              const char* channel);
  void SendReply(const std::string& client_id, int64_t request_id, const Status& status, const std::string& message,
                 const std::vector<int64_t>& ids = {});
  bool DrainInbox();  // true if a command changed the world
  bool Apply(Command& cmd);
  void StepWorld();
  void FinishStepCommands();
  void CancelStepCommands(const std::string& why);
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
  std::atomic<int64_t> accepted_{0}, rejected_{0};
  std::string last_error_;  // guarded by mutex_

  // simulation thread only
  World world_;
  CollisionDetector detector_;
  std::shared_ptr<ContactMethod> method_;
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
  };
  std::deque<PendingStep> pending_steps_;
  int64_t step_budget_ = 0;
  Journal journal_;
  SnapshotStore snapshots_;
  bool replaying_ = false;         // applying journal records: no replies, no journaling
  bool hold_replies_ = false;      // a batch is being applied: reply after the journal sync
  bool last_reply_ok_ = false;     // the status of the last SendReply
  std::vector<std::vector<uint8_t>> held_replies_;
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
