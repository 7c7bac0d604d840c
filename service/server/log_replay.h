// Re-simulation of a recorded run (`contactsim-server --replay LOG`): the
// command channels of an lcm-logger log (command_channels.h) are fed, in
// their logged order, through the server's own decoding and applying path
// (SimServer::OnMessage) into a fresh world, and every
// logged STATE's state_hash is compared with the re-simulated world's.
//
// When a command applies: the live server applied it at the step boundary
// its REPLY names (reply.step) and published that reply before any later
// STATE. So a command is fed when its reply appears in the log, after the
// world has stepped to reply.step. This is exact in every mode, also in
// REALTIME where STATE is decimated and a command lands between two logged
// STATEs. A command whose reply is an error changed nothing and is not fed.
// (For RESET, LOAD_SCENE, RESTORE and REWIND reply.step is the step
// after the command; stepping towards it first is harmless, as the world is
// replaced.) A STATE says how far the world has stepped: the replay steps
// to state.step and compares. A lockstep input gets no reply when accepted;
// it is offered when logged, as the live server queued it, and applies at
// its step. Drake's arm and gripper driver commands (arm_driver/) come on
// the channels the config names; the server answers an accepted one on
// REPLY (client_id the channel, request_id the command's utime, step where
// it applied), so they are fed at their reply like the commands above.
//
// What the channels cannot carry shows as a divergence at the step it
// touches: an input that a `reuse` late policy applied again (a wall-clock
// decision; the journal has it, the channels do not), and messages the
// logger lost (UDP). The log must begin before the first command that
// changed the world, or with a RESET or LOAD_SCENE.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>

#include "service/physics/status.h"
#include "service/server/sim_server.h"

namespace contactsim {

struct ServerSetup;

struct ReplayReport {
  int64_t states_compared = 0;
  // STATEs this build's state_t does not decode: a log recorded by a
  // contactsim whose STATE had another layout (its fingerprint differs)
  int64_t states_undecodable = 0;
  int64_t commands_fed = 0;   // command messages applied at their reply
  int64_t inputs_fed = 0;     // lockstep inputs offered
  int64_t unanswered = 0;     // commands without a reply in the log: not fed
  int64_t first_step = -1, last_step = -1;  // of the compared STATEs
  bool diverged = false;
  int64_t divergent_step = 0;                // the logged STATE's step
  int64_t replayed_step = 0;                 // where the replay was (differs if the log skips back)
  uint64_t logged_hash = 0, replayed_hash = 0;
  uint64_t logged_digest = 0, replayed_digest = 0;  // lockstep input digests of that step
  std::string last_command;                  // the last command fed before the divergence
  // One line per fact, for the terminal.
  std::string Summary() const;
};

class LogReplayer {
 public:
  // `server` is fresh (Init done) and never Run: the replayer steps it.
  explicit LogReplayer(SimServer* server);

  // One logged event, in log order. Returns false once a divergence has
  // been found: the rest of the log tells nothing more.
  bool OnEvent(const std::string& channel, const void* data, int size);
  // Counts what never got a reply; the report is final after this.
  const ReplayReport& Finish();
  const ReplayReport& report() const { return report_; }

 private:
  struct Pending {
    std::string channel;
    std::string label;  // the command channel's suffix, or a driver's channel
    std::string payload;
  };
  void OnCommand(const std::string& channel_name, const CommandChannel& channel, const void* data, int size);
  void OnDriverCommand(const std::string& channel_name, RecordKind record, const void* data, int size);
  void OnReply(const void* data, int size);
  void OnState(const void* data, int size);
  void StepTo(int64_t step);

  SimServer* server_;
  std::string reply_, state_;                          // channel names
  std::map<std::string, const CommandChannel*> channels_;  // the command channels, by full name
  std::map<std::string, RecordKind> drivers_;              // the drivers' command channels
  // commands waiting for their reply, by (client id, request id), oldest
  // first (a driver's utime may repeat); ordered containers only
  // (determinism)
  std::map<std::pair<std::string, int64_t>, std::deque<Pending>> pending_;
  ReplayReport report_;
};

// Reads the log at `path` (lcm::LogFile) event by event into `replayer`;
// an error names the file when it cannot be read.
Status ReplayLogFile(const std::string& path, LogReplayer* replayer);

// `contactsim-server --replay LOG`: a fresh server from `setup` (no journal,
// no network, no snapshot files written), the log replayed into it, the
// summary printed. Exit code: 0 identical, 2 diverged, 1 error.
int RunReplay(ServerSetup setup, const std::string& log_path);

}  // namespace contactsim
