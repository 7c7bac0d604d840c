// Tests of lockstep co-simulation: the scheduler's late policies (no
// threads, explicit waiting times) and the server's lockstep steps through
// a recording transport.
#include "service/server/lockstep.h"

#include <gtest/gtest.h>

#include <contactsim/state_t.hpp>

#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

ControllerInput Input(const std::string& who, int64_t step, double fz) {
  ControllerInput in;
  in.controller = who;
  in.step = step;
  in.bodies.push_back({2, Vec3(0, 0, fz), Vec3::Zero()});
  return in;
}

// Verifies that a resend of the input just applied (a controller answering
// a repeated STATE after its input had already arrived) is ignored quietly,
// while any other input for a taken step is still refused.
TEST(LockstepTest, ResendOfTheAppliedInputIsIgnored) {
  Lockstep l;
  ASSERT_TRUE(l.Register("a", LatePolicy::kWait, 0.1).ok());
  ControllerInput in = Input("a", 3, 1.0);
  in.request_id = 17;
  ASSERT_TRUE(l.Offer(in, 3).ok());
  ASSERT_EQ(l.Take(3).size(), 1u);
  EXPECT_TRUE(l.Offer(in, 4).ok());
  EXPECT_FALSE(l.Ready(4));  // the resend queued nothing
  in.request_id = 18;
  EXPECT_EQ(l.Offer(in, 4).code(), StatusCode::kFailedPrecondition);
}

// Verifies that a step is ready only when every controller has its input,
// in controller id order, and that stale inputs are refused.
TEST(LockstepTest, ReadyOnlyWithEveryControllersInput) {
  Lockstep l;
  ASSERT_TRUE(l.Register("b", LatePolicy::kWait, 0.1).ok());
  ASSERT_TRUE(l.Register("a", LatePolicy::kWait, 0.1).ok());
  EXPECT_FALSE(l.Ready(5));
  ASSERT_TRUE(l.Offer(Input("b", 5, 1.0), 5).ok());
  EXPECT_FALSE(l.Ready(5));
  ASSERT_TRUE(l.Offer(Input("a", 5, 2.0), 5).ok());
  EXPECT_TRUE(l.Ready(5));
  EXPECT_EQ(l.Offer(Input("c", 5, 0), 5).code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(l.Offer(Input("a", 4, 0), 5).message().find("came after it was taken"), std::string::npos);
  const auto taken = l.Take(5);
  ASSERT_EQ(taken.size(), 2u);
  EXPECT_EQ(taken[0].controller, "a");
  EXPECT_NE(DigestInputs(taken), 0u);
  EXPECT_EQ(DigestInputs({}), 0u);
  EXPECT_FALSE(l.Ready(6));
}

// Verifies each late policy: wait never decides, reuse repeats the last
// input after its timeout, drop releases the controller; each decision is
// counted and described.
TEST(LockstepTest, LatePoliciesActAfterTheirTimeouts) {
  Lockstep l;
  ASSERT_TRUE(l.Register("w", LatePolicy::kWait, 0.01).ok());
  ASSERT_TRUE(l.Register("r", LatePolicy::kReuse, 0.05).ok());
  ASSERT_TRUE(l.Register("d", LatePolicy::kDrop, 0.2).ok());
  for (const char* who : {"w", "r", "d"}) ASSERT_TRUE(l.Offer(Input(who, 1, 7.0), 1).ok());
  l.Take(1);
  ASSERT_TRUE(l.Offer(Input("w", 2, 1.0), 2).ok());
  EXPECT_DOUBLE_EQ(l.NextDeadline(2), 0.05);
  EXPECT_TRUE(l.ResolveLate(2, 0.04).empty());
  auto lines = l.ResolveLate(2, 0.06);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("\"r\" late for step 2"), std::string::npos) << lines[0];
  EXPECT_FALSE(l.Ready(2));  // d still missing
  EXPECT_DOUBLE_EQ(l.NextDeadline(2), 0.2);
  lines = l.ResolveLate(2, 0.25);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("dropped"), std::string::npos);
  EXPECT_TRUE(l.Ready(2));
  EXPECT_EQ(l.size(), 2u);
  const auto taken = l.Take(2);
  ASSERT_EQ(taken.size(), 2u);
  EXPECT_EQ(taken[0].controller, "r");
  EXPECT_EQ(taken[0].step, 2);
  EXPECT_EQ(taken[0].bodies[0].force.z(), 7.0);  // the reused input
  EXPECT_EQ(l.late_events(), 2);
  EXPECT_NE(l.Describe().find("r (reuse, 0.05 s, late 1)"), std::string::npos) << l.Describe();
}

// Verifies the server side: in lockstep mode no step is taken before the
// controller's input; the input acts for its one step (dv = F dt / m); the
// STATE carries its digest; and a rewind replays the journaled inputs to the
// same hashes.
TEST(LockstepServerTest, StepsWaitForInputsWhichActForOneStepAndReplay) {
  ServerOptions options;
  options.prefix = "L";
  ServerHarness h(options);
  scene_cmd_t g = h.Scene(scene_cmd_t::SET_GRAVITY);
  ASSERT_EQ(h.Send(g).code, reply_t::OK);  // zero gravity
  body_cmd_t add = h.Box(0.1, Vec3(0, 0, 1));
  add.mass = 2.0;
  ASSERT_EQ(h.Send(add).code, reply_t::OK);  // body 1
  scene_cmd_t reg = h.Scene(scene_cmd_t::REGISTER_CONTROLLER);
  reg.client_id = "ctl";
  ASSERT_EQ(h.Send(reg).code, reply_t::OK);
  scene_cmd_t mode = h.Scene(scene_cmd_t::SET_MODE);
  mode.mode = scene_cmd_t::LOCKSTEP;
  ASSERT_EQ(h.Send(mode).code, reply_t::OK);
  ASSERT_EQ(h.Send(h.Scene(scene_cmd_t::RESUME)).code, reply_t::OK);

  EXPECT_FALSE(h.server.Tick());  // no input for step 1 yet
  EXPECT_EQ(h.server.world().step, 0);
  std::vector<uint64_t> hashes;
  for (int k = 1; k <= 6; ++k) {
    input_t in{};
    in.client_id = "ctl";
    in.step = k;
    if (k != 3) {  // step 3: "no input"
      in.body_ids = {1};
      in.forces = {{4.0, 0.0, 0.0}};
      in.torques = {{0.0, 0.0, 0.0}};
    }
    h.Post(in);
    ASSERT_TRUE(h.server.Tick()) << k;
    ASSERT_EQ(h.server.world().step, k);
    const state_t st = h.transport.All<state_t>("L_STATE").back();
    EXPECT_EQ(st.step, k);
    EXPECT_NE(st.input_digest, 0) << k;
    hashes.push_back(HashWorldState(h.server.world()));
  }
  // five steps of 4 N on 2 kg for 1/240 s each
  EXPECT_NEAR(h.server.world().Find(1)->LinearVelocity().x(), 5 * 4.0 / 2.0 / 240.0, 1e-12);
  EXPECT_FALSE(h.server.Tick());

  // inputs are commands like any other for the journal: a rewind replays them
  scene_cmd_t rewind = h.Scene(scene_cmd_t::REWIND);
  for (int target : {5, 2}) {
    rewind.target_step = target;
    const reply_t r = h.Send(rewind);
    ASSERT_EQ(r.code, reply_t::OK) << r.message;
    EXPECT_EQ(HashWorldState(h.server.world()), hashes[target - 1]) << target;
  }
}

}  // namespace
}  // namespace contactsim
