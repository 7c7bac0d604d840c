// Tests of the server's loop in lockstep with its two threads: the
// simulation thread in SimServer::Run and this thread in the LCM thread's
// place (SimServer::OnMessage), with lockstep_step_on_input on and off
// (sim_server.h: the step is taken on the thread that receives the input
// while the simulation thread waits for it).
#include <gtest/gtest.h>

#include <contactsim/body_cmd_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/state_t.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "service/contact/contact_method_registry.h"
#include "service/server/sim_server.h"
#include "tests/server/recording_transport.h"

namespace contactsim {
namespace {

using testing::Encode;

// Records STATE (with the thread that published it) and REPLY from both
// threads, and lets the test wait for one.
class WaitableTransport : public Transport {
 public:
  struct Published {
    state_t state;
    std::thread::id thread;
  };
  void Publish(const std::string& channel, const void* data, int size) override {
    std::lock_guard<std::mutex> lock(mutex_);
    if (channel == "W_STATE") {
      Published p;
      p.state.decode(data, 0, size);
      p.thread = std::this_thread::get_id();
      states_.push_back(p);
    } else if (channel == "W_REPLY") {
      reply_t r;
      r.decode(data, 0, size);
      replies_.push_back(r);
    }
    changed_.notify_all();
  }
  // The reply to `request_id`, waiting up to 30 s for it (a reply with code -1 if none came).
  reply_t Reply(int64_t request_id) {
    reply_t found{};
    found.code = -1;
    Await([&] {
      for (const reply_t& r : replies_) {
        if (r.request_id == request_id) return found = r, true;
      }
      return false;
    });
    return found;
  }
  // The first STATE of `step`, waiting up to 30 s for it (step -1 if none came).
  Published State(int64_t step) {
    Published found;
    found.state.step = -1;
    Await([&] {
      for (const Published& p : states_) {
        if (p.state.step == step) return found = p, true;
      }
      return false;
    });
    return found;
  }
  // Whether a STATE of `step` was published, without waiting.
  bool HasState(int64_t step) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const Published& p : states_) {
      if (p.state.step == step) return true;
    }
    return false;
  }

 private:
  void Await(const std::function<bool()>& found) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, std::chrono::seconds(30), found);
  }
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<Published> states_;
  std::vector<reply_t> replies_;
};

// A server whose simulation thread runs Run while the test sends it
// commands from its own thread.
class RunningServer {
 public:
  explicit RunningServer(bool step_on_input) : server_(Options(step_on_input), &transport) {
    std::shared_ptr<ContactMethod> method;
    EXPECT_TRUE(MakeContactMethod("impulse", {}, &method).ok());
    EXPECT_TRUE(server_.Init(nullptr, method).ok());
    thread_ = std::thread([this] { server_.Run(stop_); });
  }
  ~RunningServer() {
    stop_ = true;
    thread_.join();
  }
  static ServerOptions Options(bool step_on_input) {
    ServerOptions o;
    o.prefix = "W";
    o.start_paused = true;
    o.mode = RunMode::kFreeRun;
    o.live_line = false;
    o.lockstep_step_on_input = step_on_input;
    return o;
  }
  // Sends a command and waits for its reply.
  template <typename Msg>
  reply_t Send(Msg m, const char* channel, const char* client = "test") {
    m.client_id = client;
    m.request_id = ++request_id_;
    Post(m, channel);
    return transport.Reply(m.request_id);
  }
  template <typename Msg>
  void Post(const Msg& m, const char* channel) {
    const auto bytes = Encode(m);
    server_.OnMessage(server_.Channel(channel), bytes.data(), static_cast<int>(bytes.size()));
  }
  reply_t Scene(int8_t op, int8_t mode = 0, int32_t steps = 0) {
    scene_cmd_t m{};
    m.op = op;
    m.mode = mode;
    m.steps = steps;
    return Send(m, "SCENE_CMD");
  }
  // An input of `fx` N along x on body 1 for `step`, from controller "ctl".
  void Input(int64_t step, double fx, int64_t request_id) {
    input_t in{};
    in.client_id = "ctl";
    in.request_id = request_id;
    in.step = step;
    in.num_bodies = 1;
    in.body_ids = {1};
    in.forces = {{fx, 0.0, 0.0}};
    in.torques = {{0.0, 0.0, 0.0}};
    Post(in, "INPUT");
  }
  std::thread::id sim_thread() const { return thread_.get_id(); }

  WaitableTransport transport;

 private:
  SimServer server_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  int64_t request_id_ = 0;
};

// A free box of 2 kg without gravity and a controller "ctl", in lockstep.
void StartLockstep(RunningServer& s) {
  scene_cmd_t g{};
  g.op = scene_cmd_t::SET_GRAVITY;
  ASSERT_EQ(s.Send(g, "SCENE_CMD").code, reply_t::OK);
  body_cmd_t add{};
  add.op = body_cmd_t::ADD;
  add.shape = body_cmd_t::BOX;
  add.mass = 2.0;
  add.orientation[0] = 1.0;
  for (int i = 0; i < 3; ++i) add.half_extents[i] = 0.1;
  add.position[2] = 1.0;
  ASSERT_EQ(s.Send(add, "BODY_CMD").code, reply_t::OK);
  scene_cmd_t reg{};
  reg.op = scene_cmd_t::REGISTER_CONTROLLER;
  ASSERT_EQ(s.Send(reg, "SCENE_CMD", "ctl").code, reply_t::OK);
  ASSERT_EQ(s.Scene(scene_cmd_t::SET_MODE, scene_cmd_t::LOCKSTEP).code, reply_t::OK);
  ASSERT_EQ(s.Scene(scene_cmd_t::RESUME).code, reply_t::OK);
}

struct LockstepRun {
  std::vector<int64_t> hashes;  // STATE k's, k = 1..n
  int on_input_thread = 0;      // STATEs published by the thread that sent the input
  int on_sim_thread = 0;
  double velocity = 0.0;        // the box's along x in the last STATE
};

// n cycles: STATE k-1, then the input for k (4 N, none at k = 3).
LockstepRun Cycles(RunningServer& s, int n) {
  LockstepRun run;
  for (int k = 1; k <= n; ++k) {
    EXPECT_EQ(s.transport.State(k - 1).state.step, k - 1);
    s.Input(k, k == 3 ? 0.0 : 4.0, 5000 + k);
    const WaitableTransport::Published p = s.transport.State(k);
    EXPECT_EQ(p.state.step, k);
    EXPECT_NE(p.state.input_digest, 0);
    run.hashes.push_back(p.state.state_hash);
    run.on_input_thread += p.thread == std::this_thread::get_id();
    run.on_sim_thread += p.thread == s.sim_thread();
    run.velocity = p.state.bodies.at(0).linear_velocity[0];
  }
  return run;
}

// Verifies that the steps taken on the input's thread are those the
// simulation thread takes, bit for bit (the same STATE hashes, the inputs
// acting for one step each: dv = F dt / m), and that with the option on
// the input's thread takes them while the simulation thread sleeps (it
// takes one itself only when its wait happens to end as the input comes).
TEST(LockstepTurnTest, StepsOnTheInputsThreadAreTheSimulationThreads) {
  constexpr int kSteps = 60;
  LockstepRun runs[2];
  for (bool on : {false, true}) {
    RunningServer s(on);
    StartLockstep(s);
    runs[on] = Cycles(s, kSteps);
    if (on) {
      EXPECT_GE(runs[on].on_input_thread, kSteps / 2);
    } else {
      EXPECT_EQ(runs[on].on_input_thread, 0);
      EXPECT_EQ(runs[on].on_sim_thread, kSteps);
    }
  }
  EXPECT_EQ(runs[0].hashes, runs[1].hashes);
  EXPECT_NEAR(runs[1].velocity, (kSteps - 1) * 4.0 / 2.0 / 240.0, 1e-12);
}

// Verifies the lockstep guarantees with the option on: an input for a step
// already taken is refused with the reason and takes no step; a PAUSE that
// arrives while the simulation thread waits for inputs stops the steps;
// and the commands that take the loop out of lockstep (FREE_RUN, STEP) are
// run by the simulation thread, which the input's thread wakes.
TEST(LockstepTurnTest, RefusedInputsAndCommandsWhileWaitingKeepTheirGuarantees) {
  RunningServer s(true);
  StartLockstep(s);
  Cycles(s, 5);
  s.Input(4, 4.0, 777);  // step 4 is taken
  const reply_t late = s.transport.Reply(777);
  EXPECT_EQ(late.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(late.message.find("input for step 4 came after it was taken"), std::string::npos) << late.message;
  EXPECT_EQ(late.step, 5);

  ASSERT_EQ(s.Scene(scene_cmd_t::PAUSE).code, reply_t::OK);
  s.Input(6, 4.0, 778);  // queued for step 6; paused: no step
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  EXPECT_FALSE(s.transport.HasState(6)) << "a paused server stepped";

  ASSERT_EQ(s.Scene(scene_cmd_t::SET_MODE, scene_cmd_t::FREE_RUN).code, reply_t::OK);
  const reply_t stepped = s.Scene(scene_cmd_t::STEP, 0, 10);
  EXPECT_EQ(stepped.code, reply_t::OK) << stepped.message;
  EXPECT_EQ(stepped.step, 15);
}

// Verifies that a late policy still acts after its timeout when the steps
// are taken on the input's thread: a second controller that never answers,
// registered with "drop" and 20 ms, holds the steps back until the
// simulation thread's wait reaches its deadline and drops it; the steps
// then go on with "ctl"'s inputs alone, which all act.
TEST(LockstepTurnTest, LatePoliciesActWhileTheInputsThreadTakesTheSteps) {
  RunningServer s(true);
  StartLockstep(s);
  Cycles(s, 3);
  scene_cmd_t reg{};
  reg.op = scene_cmd_t::REGISTER_CONTROLLER;
  reg.late_policy = scene_cmd_t::LATE_DROP;
  reg.late_timeout = 0.02;
  ASSERT_EQ(s.Send(reg, "SCENE_CMD", "silent").code, reply_t::OK);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 4; k <= 8; ++k) {
    s.Input(k, 4.0, 6000 + k);
    ASSERT_EQ(s.transport.State(k).state.step, k);
  }
  // step 4 waited for the silent controller's timeout, the others did not
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(20));
  // seven steps of 4 N (step 3 had none) on 2 kg for 1/240 s each
  EXPECT_NEAR(s.transport.State(8).state.bodies.at(0).linear_velocity[0], 7 * 4.0 / 2.0 / 240.0, 1e-12);
  const reply_t paused = s.Scene(scene_cmd_t::PAUSE);
  ASSERT_EQ(paused.code, reply_t::OK);
  EXPECT_EQ(paused.step, 8);
}

// Verifies that releasing the last controller while the simulation thread
// waits hands the loop back to it: a lockstep world without controllers
// runs free on the simulation thread, and the input's thread returns to
// its messages (a PAUSE is answered, the steps stop).
TEST(LockstepTurnTest, ReleasingTheLastControllerHandsTheStepsBack) {
  RunningServer s(true);
  StartLockstep(s);
  Cycles(s, 3);
  scene_cmd_t release{};
  release.op = scene_cmd_t::RELEASE_CONTROLLER;
  ASSERT_EQ(s.Send(release, "SCENE_CMD", "ctl").code, reply_t::OK);
  // STATE at state_rate_hz now: every 4th step at 60 Hz and dt 1/240 s
  const WaitableTransport::Published free = s.transport.State(100);
  EXPECT_EQ(free.state.step, 100);
  EXPECT_EQ(free.thread, s.sim_thread());
  const reply_t paused = s.Scene(scene_cmd_t::PAUSE);
  ASSERT_EQ(paused.code, reply_t::OK);
  EXPECT_GE(paused.step, 100);
}

}  // namespace
}  // namespace contactsim
