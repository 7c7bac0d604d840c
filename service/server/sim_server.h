// The server's core, independent of LCM. It owns the world and fronts the
// parts that own the rest of the server's state, each with one job:
//
//   CommandIntake  LCM thread: signatures, decoding and the checks that need
//                  no world, rate limits; good commands go to the inbox
//   CommandBatch   the inbox, and each batch applied at a step boundary with
//                  its journal records, group commit, undo and held replies
//   StepRequests   STEP commands in flight, the step budget, REWIND progress
//   LockstepGate   controllers, their inputs and the wait for them
//   Publisher      the outgoing channels, their rates, PROGRESS, live line
//
// SimServer keeps the world, the contact method, the collision detector,
// sleeping, the commands on the world and the loop (Run). One thread at a
// time touches the world, the one that holds the loop's turn, so the engine
// needs no locks: the simulation thread, except while it waits for lockstep
// inputs with lockstep_step_on_input, when the LCM thread takes the turn for
// the message it received and steps as soon as the inputs are complete (no
// wake-up of a sleeping thread between the input and the step). Otherwise
// the two threads share only the batch's inbox and counters.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "service/collision/collision_detector.h"
#include "service/contact/contact_method.h"
#include "service/contact/sleep/island_sleep.h"
#include "service/physics/runaway_watch.h"
#include "service/physics/world.h"
#include "service/proto/snapshot.pb.h"
#include "service/scene/scene_spec.h"
#include "service/server/arm_driver/arm_driver.h"
#include "service/server/arm_driver/wsg_driver.h"
#include "service/server/command.h"
#include "service/server/command_batch.h"
#include "service/server/command_intake.h"
#include "service/server/lockstep_gate.h"
#include "service/server/outcome.h"
#include "service/server/publisher.h"
#include "service/server/server_options.h"
#include "service/server/step_requests.h"
#include "service/server/transport.h"

namespace contactsim {

class SimServer {
 public:
  SimServer(ServerOptions options, Transport* transport);

  // Builds the initial world (a null scene gives an empty one) and method;
  // with a journal folder that holds a snapshot, recovers from it instead
  // (snapshot + the journal records after it).
  Status Init(const SceneSpec* scene, std::shared_ptr<ContactMethod> method);

  // LCM thread: one payload received on `channel` (CommandIntake); takes the
  // loop's turn when the simulation thread waits for lockstep inputs. Never throws.
  void OnMessage(const std::string& channel, const void* data, int size);
  // The full names of the command channels, to subscribe to.
  std::vector<std::string> CommandChannelNames() const { return intake_.ChannelNames(); }

  // Simulation thread: runs until `stop` is set, then returns.
  void Run(const std::atomic<bool>& stop);
  // One turn of the loop without pacing, for tests: applies the inbox and,
  // unless paused with no STEP pending, takes one step. True if it stepped.
  bool Tick();

  // Re-simulation of a recorded run (log_replay.h) drives these instead of
  // Run: the commands given so far are applied now, and steps are taken
  // when the log says, without pacing or lockstep waits.
  void ApplyInbox() { batch_.Drain(); }
  void StepOnce() { StepWorld(); }
  uint64_t input_digest() const { return lockstep_.input_digest(); }  // of the last step's inputs

  std::string Channel(const char* suffix) const { return publisher_.Channel(suffix); }
  const ServerOptions& options() const { return options_; }
  const World& world() const { return world_; }
  const ContactMethod& method() const { return *method_; }
  bool paused() const { return paused_; }

 private:
  using Clock = std::chrono::steady_clock;

  // the commands on the world, called by the batch
  Outcome Apply(Command& cmd);
  Outcome ApplyBodyCommand(Command& cmd);  // bodies and joints (body_commands.cpp)
  Outcome ApplyToBody(Command& cmd, RigidBody* b);
  RigidBody* FindBody(BodyId id, bool need_dynamic, Status* status);
  Outcome ApplyWorldCommand(Command& cmd);  // scene, method, running (world_commands.cpp)
  Outcome ApplySnapshotCommand(Command& cmd);  // snapshot, restore, rewind (snapshot_commands.cpp)
  Outcome ApplySensorCommand(Command& cmd);    // add and remove sensors (sensor_commands.cpp)
  Outcome ApplyRayCast(Command& cmd);          // a batch of rays, answered on RAY_HITS
  Outcome ApplyModelCommand(Command& cmd);  // load, remove, info (model_commands.cpp)
  Outcome LoadModel(Command& cmd);
  // Drake's arm driver (arm_driver/sim_server_arm.cpp): at start, loads its
  // model when configured and holds the arm; then its commands and status.
  Status StartArmDriver();
  Outcome ApplyArmCommand(Command& cmd);
  void PublishArmStatus();
  // What both drivers do at start: refuse a server with an auth key (Drake's
  // messages carry no signature), and load `load` unless the world holds
  // `model`; *present says whether the world holds it now. `block` names the
  // config block in errors.
  Status StartDriverModel(const char* block, const std::string& model,
                          const std::optional<proto::SceneModel>& load, bool* present);
  // Drake's Schunk WSG driver (arm_driver/sim_server_wsg.cpp), alike.
  Status StartWsgDriver();
  Outcome ApplyWsgCommand(Command& cmd);
  void PublishWsgStatus();
  Status CheckNotInModel(BodyId body, JointId joint) const;
  // MODEL_INFO, when the models changed since the last one or it was asked for
  void PublishModelInfo();
  // joints' actuators (actuator_commands.cpp): SET and CLEAR of the standing
  // settings; a lockstep input's joints checked against the world and, at
  // its step, applied over the standing settings, which return after it
  Outcome ApplyActuatorCommand(Command& cmd);
  Status CheckInputJoints(ControllerInput* input) const;
  void ApplyInputJoints(const ControllerInput& input, bool live);
  void RestoreStandingActuators();
  void PublishJointState();
  // the timeline: recovery, snapshots and rewind (timeline.cpp)
  Status Recover();
  proto::Snapshot SaveDurableSnapshot();
  void StartTimeline();
  void TakePeriodicSnapshot();
  Status Rewind(int64_t step, const Command* cmd = nullptr);
  Status ReplayRecord(const JournalRecord& record);
  // Puts `world` and `method` in place, with sleeping's caches dropped and
  // the detector's replaced by `manifolds` (a snapshot's kept manifolds,
  // service/scene/snapshot_manifolds.h; none for a new world).
  void ReplaceWorld(World&& world, std::shared_ptr<ContactMethod> method,
                    std::vector<CachedManifold> manifolds = {});
  // A snapshot of the world, the method and the detector's kept manifolds.
  proto::Snapshot SaveState() const;
  // After the world was replaced: no contacts, rates of its time step, and
  // its state the base of REWIND and recovery.
  void StartOver();

  // the loop: one turn applies the inbox and takes a step if one is due;
  // otherwise it says what the loop waits for, and *until how long at most
  enum class Pause { kNone, kForCommands, kForInputs };
  Pause Turn(Clock::time_point* until, bool lockstep_only);
  // LCM thread, with the turn: the turns the simulation thread would take
  // for the message just queued; wakes it if its wait no longer fits.
  void TurnOnInput();
  void StepWorld();
  // A step that blew up (runaway_watch.h): its state is not published, the
  // running STEPs are answered with the reason, STATUS carries it at once,
  // and stepping stops until a command replaces the world (ClearFault).
  void OnBlowUp(const Status& why);
  void ClearFault();
  Status RefusedByFault() const;
  void SimulateStep();
  void ApplyInputs();
  void ApplyInput(const ControllerInput& input, bool live);
  bool LockstepReady(Clock::time_point* until);  // null: Tick (no clock)
  void FinishStepCommands();
  void CancelStepCommands(const std::string& why);
  bool Halted() const { return paused_ && !steps_.owed(); }  // paused with no STEP to take
  void PublishState();    // and the sensors' readings with it
  void PublishSensors();
  void PublishStatus(Clock::time_point now);

  const ServerOptions options_;
  World world_;
  CollisionDetector detector_;
  std::shared_ptr<ContactMethod> method_;
  IslandSleep sleep_;
  ContactSet contacts_;
  StepStats last_stats_;
  RunawayWatch runaway_;
  // the standing settings of the joints a lockstep input overrides for the
  // step about to be taken, put back after it (RestoreStandingActuators)
  std::vector<std::pair<JointId, JointActuator>> standing_actuators_;
  uint64_t models_published_ = 0;  // signature of the model list MODEL_INFO last carried
  bool model_info_due_ = true;      // at start, and on INFO
  std::string fault_;  // "" while the world is sound; STATUS.fault
  bool paused_;
  RunMode mode_;
  double real_time_factor_;
  bool reanchor_ = true;  // REALTIME pacing starts again from now
  Clock::time_point wall_anchor_;  // REALTIME: step k is due at wall_anchor_ + (time - sim_anchor_) / rtf
  double sim_anchor_ = 0.0;
  Clock::duration status_period_;
  Clock::time_point next_status_;

  // The loop's turn: held by the simulation thread in Run except while it
  // waits for lockstep inputs (parked_, until parked_until_), when the LCM
  // thread may take it (OnMessage).
  std::mutex turn_mutex_;
  std::atomic<bool> parked_{false};
  Clock::time_point parked_until_;

  std::unique_ptr<ArmDriver> arm_;  // null without an arm_driver block
  std::unique_ptr<WsgDriver> wsg_;  // null without a wsg_driver block

  Publisher publisher_;
  StepRequests steps_;
  CommandBatch batch_;
  LockstepGate lockstep_;
  CommandIntake intake_;
};

}  // namespace contactsim
