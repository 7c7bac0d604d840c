// Tests of LogReplayer: a live server on a recording transport is driven
// through commands, STEPs and lockstep inputs while every message is taped
// in order (as lcm-logger would log them); the tape, replayed into a fresh
// server, must agree at every STATE, and a tampered tape must not.
#include "service/server/log_replay.h"

#include <gtest/gtest.h>

#include <contactsim/body_cmd_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/state_t.hpp>
#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "service/contact/contact_method.h"
#include "service/contact/contact_method_registry.h"
#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::Encode;
using testing::ServerHarness;
using Tape = std::vector<std::pair<std::string, std::vector<uint8_t>>>;

// A live run taped in log order: each command as sent, then whatever the
// server published while applying it.
class LiveRun {
 public:
  explicit LiveRun(ServerOptions options = {}) : live_(options) {}

  template <typename Msg>
  void Send(Msg m, const char* channel) {
    live_.Post(m);
    tape_.push_back({live_.server.Channel(channel), Encode(m)});
    while (live_.server.Tick()) {}
    Collect();
  }
  void Step(int n) {
    scene_cmd_t m = live_.Scene(scene_cmd_t::STEP);
    m.steps = n;
    Send(m, "SCENE_CMD");
  }
  // One lockstep step with the controller's force on body 2.
  void Input(double fx) {
    input_t m{};
    m.client_id = "test";
    m.step = live_.server.world().step + 1;
    m.body_ids = {2};
    m.forces = {{fx, 0.0, 0.0}};
    m.torques = {{0.0, 0.0, 0.0}};
    live_.Post(m);
    tape_.push_back({live_.server.Channel("INPUT"), Encode(m)});
    ASSERT_TRUE(live_.server.Tick());
    Collect();
  }
  void Collect() {
    auto& all = live_.transport.messages;
    for (; seen_ < all.size(); ++seen_) tape_.push_back(all[seen_]);
  }
  // A box on a plane, gravity changed, an impulse, STEPs and 10 lockstep
  // steps with a controller's forces.
  void Record() {
    Collect();  // Init's STATE at step 0
    body_cmd_t plane = live_.Body(body_cmd_t::ADD);
    plane.shape = body_cmd_t::PLANE;
    plane.plane_normal[2] = 1.0;
    Send(plane, "BODY_CMD");
    Send(live_.Box(0.1, Vec3(0, 0, 0.5)), "BODY_CMD");  // id 2
    Step(30);
    body_cmd_t kick = live_.Body(body_cmd_t::APPLY_IMPULSE, 2);
    kick.impulse[0] = 0.5;
    kick_index_ = tape_.size();
    Send(kick, "BODY_CMD");
    scene_cmd_t g = live_.Scene(scene_cmd_t::SET_GRAVITY);
    g.gravity[2] = -5.0;
    Send(g, "SCENE_CMD");
    Step(20);
    Send(live_.Scene(scene_cmd_t::REGISTER_CONTROLLER), "SCENE_CMD");
    scene_cmd_t mode = live_.Scene(scene_cmd_t::SET_MODE);
    mode.mode = scene_cmd_t::LOCKSTEP;
    Send(mode, "SCENE_CMD");
    Send(live_.Scene(scene_cmd_t::RESUME), "SCENE_CMD");
    for (int i = 0; i < 10; ++i) {
      input_index_.push_back(tape_.size());
      Input(2.0 + i);
    }
    Send(live_.Scene(scene_cmd_t::PAUSE), "SCENE_CMD");
    Send(live_.Scene(scene_cmd_t::RELEASE_CONTROLLER), "SCENE_CMD");
    mode.mode = scene_cmd_t::FREE_RUN;
    Send(mode, "SCENE_CMD");
    Step(10);
  }

  // The determinism scene (config/scenes/determinism.pbtxt) loaded, then
  // every registered contact method in turn, lcp with each of its solvers,
  // `steps` steps each: a run that switches methods mid-run
  // (docs/snapshots.md, "Determinism across builds"). The barrier method
  // simulates no joints and no restitution and refuses a world with either
  // (method_contract.h), so the scene's two joints are removed and every
  // body's restitution set to 0 before the switch to it (the bob and the
  // door fall).
  void RecordEveryMethod(int steps) {
    Collect();
    scene_cmd_t load = live_.Scene(scene_cmd_t::LOAD_SCENE);
    load.path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/determinism.pbtxt";
    Send(load, "SCENE_CMD");
    for (const std::string& name : ContactMethodNames()) {
      const std::vector<std::string> solvers =
          name == "lcp" ? std::vector<std::string>{"pgs", "lemke"} : std::vector<std::string>{""};
      const MethodContract& contract = FindContactMethod(name)->contract;
      if (!contract.joints) RemoveJoints();
      if (!contract.restitution) RemoveRestitution();
      for (const std::string& solver : solvers) {
        scene_cmd_t m = live_.Scene(scene_cmd_t::SET_METHOD);
        m.method = name;
        if (!solver.empty()) {
          m.param_names = {"solver"};
          m.param_values = {solver};
          m.num_params = 1;
        }
        Send(m, "SCENE_CMD");
        Step(steps);
      }
    }
  }
  // A stack of two boxes under the server's default method, the lower one
  // of category 2 given at ADD, the upper one's mask set to the ground's
  // category by SET_FILTER after 100 steps: it falls through the lower box.
  void RecordFilterChange() {
    Collect();
    body_cmd_t plane = live_.Body(body_cmd_t::ADD);
    plane.shape = body_cmd_t::PLANE;
    plane.plane_normal[2] = 1.0;
    Send(plane, "BODY_CMD");
    body_cmd_t lower = live_.Box(0.1, Vec3(0, 0, 0.101));
    lower.has_filter = true;
    lower.collision_category = 2;
    lower.collision_mask = -1;
    Send(lower, "BODY_CMD");
    Send(live_.Box(0.1, Vec3(0, 0, 0.302)), "BODY_CMD");  // id 3
    Step(100);
    body_cmd_t filter = live_.Body(body_cmd_t::SET_FILTER, 3);
    filter.collision_category = 1;
    filter.collision_mask = 1;
    filter_index_ = tape_.size();
    Send(filter, "BODY_CMD");
    Step(100);
  }
  double z(BodyId id) const { return live_.server.world().Find(id)->x.z(); }
  size_t filter_index() const { return filter_index_; }
  // Sets every body's restitution to 0 by SET_MATERIAL.
  void RemoveRestitution() {
    std::vector<BodyId> ids;
    for (const RigidBody& b : live_.server.world().bodies()) ids.push_back(b.id);
    for (BodyId id : ids) {
      body_cmd_t m = live_.Body(body_cmd_t::SET_MATERIAL, id);
      m.has_restitution = true;
      m.restitution = 0.0;
      Send(m, "BODY_CMD");
    }
  }
  // Removes every joint of the live world by JOINT_CMD.
  void RemoveJoints() {
    std::vector<JointId> ids;
    for (const Joint& j : live_.server.world().joints()) ids.push_back(j.id);
    for (JointId id : ids) {
      joint_cmd_t m{};
      m.client_id = "test";
      m.op = joint_cmd_t::REMOVE;
      m.joint_id = id;
      Send(m, "JOINT_CMD");
    }
  }
  // Whether the server accepted every command sent.
  bool AllAccepted() {
    for (const reply_t& r : live_.transport.All<reply_t>(live_.server.Channel("REPLY"))) {
      if (r.code != reply_t::OK) {
        ADD_FAILURE() << "refused: " << r.message;
        return false;
      }
    }
    return true;
  }

  const Tape& tape() const { return tape_; }
  size_t kick_index() const { return kick_index_; }
  const std::vector<size_t>& input_index() const { return input_index_; }
  int64_t final_step() const { return live_.server.world().step; }
  uint64_t final_hash() const { return HashWorldState(live_.server.world()); }

 private:
  ServerHarness live_;
  Tape tape_;
  size_t seen_ = 0;
  size_t kick_index_ = 0;
  size_t filter_index_ = 0;
  std::vector<size_t> input_index_;
};

// Replays a tape into a fresh server (same options as the live one).
ReplayReport Replay(const Tape& tape, ServerOptions options = {}) {
  ServerHarness fresh(options);
  LogReplayer replayer(&fresh.server);
  for (const auto& [channel, bytes] : tape) {
    if (!replayer.OnEvent(channel, bytes.data(), static_cast<int>(bytes.size()))) break;
  }
  return replayer.Finish();
}

int64_t CountStates(const Tape& tape, size_t from = 0) {
  int64_t n = 0;
  for (size_t i = from; i < tape.size(); ++i) n += tape[i].first == "CONTACTSIM_STATE";
  return n;
}

// The step of the first STATE on the tape after `index`.
int64_t FirstStateStepAfter(const Tape& tape, size_t index) {
  for (size_t i = index; i < tape.size(); ++i) {
    if (tape[i].first != "CONTACTSIM_STATE") continue;
    state_t s{};
    if (s.decode(tape[i].second.data(), 0, static_cast<int>(tape[i].second.size())) < 0) return -1;
    return s.step;
  }
  return -1;
}

// Verifies that replaying the tape of a run (commands, STEPs, lockstep
// inputs) reproduces every STATE's hash and input digest.
TEST(LogReplayTest, ReplayOfAnUntouchedRunIsIdentical) {
  LiveRun run;
  run.Record();
  const ReplayReport r = Replay(run.tape());
  EXPECT_FALSE(r.diverged) << r.Summary();
  EXPECT_EQ(r.states_compared, CountStates(run.tape()));
  EXPECT_EQ(r.first_step, 0);
  EXPECT_EQ(r.last_step, run.final_step());
  EXPECT_EQ(r.inputs_fed, 10);
  EXPECT_EQ(r.unanswered, 0);
  EXPECT_NE(r.Summary().find("identical"), std::string::npos);
}

// Verifies that a run through every contact method (the registry's, lcp
// with both solvers) on a scene with stacked, sliding and bouncing bodies
// and joints replays bit for bit: each method's step is a function of the
// world and the commands alone, whatever it ran after. The run ends on a
// pinned hash, the same in every build (docs/snapshots.md, "Determinism
// across builds"), so a log from one build replays on another; a change
// to any method's physics changes it (the failure prints the new one).
// With sleep on (the server's default) the rest timers join the hash, so
// each setting has its own pin; both run with manifold reuse, the default.
TEST(LogReplayTest, ReplayOfARunThroughEveryMethodIsIdentical) {
  for (const bool sleep : {false, true}) {
    SCOPED_TRACE(sleep ? "sleep on" : "sleep off");
    ServerOptions options;
    options.sleep = sleep;
    LiveRun run(options);
    run.RecordEveryMethod(20);
    ASSERT_TRUE(run.AllAccepted());
    const uint64_t pinned = sleep ? 0xa3c40d2933d2b637ull : 0x23a248d84ccaba2bull;
    EXPECT_EQ(run.final_hash(), pinned) << "got 0x" << std::hex << run.final_hash();
    const ReplayReport r = Replay(run.tape(), options);
    EXPECT_FALSE(r.diverged) << r.Summary();
    EXPECT_EQ(r.states_compared, CountStates(run.tape()));
    EXPECT_EQ(r.last_step, run.final_step());
    EXPECT_EQ(r.last_step, 20 * static_cast<int64_t>(ContactMethodNames().size() + 1));
    EXPECT_NE(r.Summary().find("identical"), std::string::npos) << r.Summary();
  }
}

// Verifies that a run with a filter given at ADD and changed by SET_FILTER
// replays bit for bit (the top box falls through the lower one in both),
// and that the tape without the SET_FILTER diverges after it (a filter is
// not part of the state hash, so at the first STATE whose poses differ).
TEST(LogReplayTest, ReplayOfARunWithAFilterChangeIsIdentical) {
  LiveRun run;
  run.RecordFilterChange();
  ASSERT_TRUE(run.AllAccepted());
  EXPECT_NEAR(run.z(3), 0.1, 0.01) << "the top box fell through";
  const ReplayReport r = Replay(run.tape());
  EXPECT_FALSE(r.diverged) << r.Summary();
  EXPECT_EQ(r.states_compared, CountStates(run.tape()));
  EXPECT_EQ(r.last_step, 200);
  Tape without = run.tape();
  without.erase(without.begin() + static_cast<long>(run.filter_index()));
  const ReplayReport cut = Replay(without);
  ASSERT_TRUE(cut.diverged);
  EXPECT_GE(cut.divergent_step, FirstStateStepAfter(run.tape(), run.filter_index()));
  EXPECT_LE(cut.divergent_step, 200);
}

// Verifies that a log whose STATEs have another state_t layout (one
// recorded before STATE carried joints: its fingerprint differs and it
// ends before the joint block) is reported as such, with every STATE
// counted as not compared, rather than as a divergence or a crash.
TEST(LogReplayTest, StatesOfAnotherLayoutAreReportedNotCompared) {
  LiveRun run;
  run.Record();
  Tape tape = run.tape();
  for (auto& [channel, bytes] : tape) {
    if (channel != "CONTACTSIM_STATE") continue;
    bytes[0] ^= 0x5a;                 // another fingerprint
    bytes.resize(bytes.size() - 4);   // no num_joints
  }
  const ReplayReport r = Replay(tape);
  EXPECT_FALSE(r.diverged) << r.Summary();
  EXPECT_EQ(r.states_compared, 0);
  EXPECT_EQ(r.states_undecodable, CountStates(run.tape()));
  const std::string text = r.Summary();
  EXPECT_NE(text.find("STATE messages are not this build's state_t"), std::string::npos) << text;
  EXPECT_NE(text.find("another version of contactsim"), std::string::npos) << text;
}

// Verifies that a tampered command (a larger impulse) is reported at the
// first STATE after it, with both hashes and the command named.
TEST(LogReplayTest, TamperedCommandIsReportedAtTheFirstStateAfterIt) {
  LiveRun run;
  run.Record();
  Tape tape = run.tape();
  auto& [channel, bytes] = tape[run.kick_index()];
  ASSERT_EQ(channel, "CONTACTSIM_BODY_CMD");
  body_cmd_t kick;
  ASSERT_GT(kick.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
  kick.impulse[0] = 0.6;
  bytes = Encode(kick);
  const ReplayReport r = Replay(tape);
  ASSERT_TRUE(r.diverged);
  EXPECT_EQ(r.divergent_step, FirstStateStepAfter(tape, run.kick_index()));
  EXPECT_NE(r.logged_hash, r.replayed_hash);
  EXPECT_EQ(r.states_compared, CountStates(tape) - CountStates(tape, run.kick_index()));
  const std::string text = r.Summary();
  EXPECT_NE(text.find("divergence at step " + std::to_string(r.divergent_step)), std::string::npos) << text;
  EXPECT_NE(text.find("last command fed before it: BODY_CMD"), std::string::npos) << text;
  EXPECT_NE(text.find("impulse on body 2"), std::string::npos) << text;
}

// Verifies that a lockstep input missing from the log (lost, or reused by a
// late policy) is reported at its step, with the input digests.
TEST(LogReplayTest, MissingInputIsReportedAtItsStepWithTheDigests) {
  LiveRun run;
  run.Record();
  Tape tape = run.tape();
  const size_t lost = run.input_index()[4];
  input_t in;
  ASSERT_GT(in.decode(tape[lost].second.data(), 0, static_cast<int>(tape[lost].second.size())), 0);
  tape.erase(tape.begin() + static_cast<long>(lost));
  const ReplayReport r = Replay(tape);
  ASSERT_TRUE(r.diverged);
  EXPECT_EQ(r.divergent_step, in.step);
  EXPECT_EQ(r.replayed_digest, 0u);
  EXPECT_NE(r.logged_digest, 0u);
  EXPECT_NE(r.Summary().find("input_digest"), std::string::npos);
}

// Verifies that ReplayLogFile reads a real LCM log file (written with
// lcm::LogFile as lcm-logger does) and that a missing file is an error.
TEST(LogReplayTest, ReadsAnLcmLogFile) {
  LiveRun run;
  run.Record();
  const std::string path = ::testing::TempDir() + "log_replay_test.lcmlog";
  {
    lcm::LogFile log(path, "w");
    ASSERT_TRUE(log.good());
    int64_t t = 0;
    for (auto& [channel, bytes] : run.tape()) {
      lcm::LogEvent e{};
      e.timestamp = ++t;
      e.channel = channel;
      e.datalen = static_cast<int32_t>(bytes.size());
      e.data = const_cast<uint8_t*>(bytes.data());
      ASSERT_EQ(log.writeEvent(&e), 0);
    }
  }
  ServerHarness fresh(ServerOptions{});
  LogReplayer replayer(&fresh.server);
  ASSERT_TRUE(ReplayLogFile(path, &replayer).ok());
  EXPECT_FALSE(replayer.Finish().diverged) << replayer.report().Summary();
  EXPECT_EQ(replayer.report().states_compared, CountStates(run.tape()));
  std::remove(path.c_str());

  LogReplayer other(&fresh.server);
  const Status st = ReplayLogFile(path, &other);
  EXPECT_EQ(st.code(), StatusCode::kNotFound);
  EXPECT_NE(st.message().find(path), std::string::npos);
}

}  // namespace
}  // namespace contactsim
