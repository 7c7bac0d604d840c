// Tests of the server logic through a recording transport, without a network.
#include "service/server/sim_server.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/server/sim_server_fixture.h"

namespace contactsim {
namespace {

using testing::Encode;
using testing::RecordingTransport;
using testing::SimServerTest;

// Verifies that ADD answers with the new id and the body appears in the world.
TEST_F(SimServerTest, AddSphereRepliesWithItsId) {
  const reply_t r = Send(Sphere(0.1, Vec3(0, 0, 1)));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  ASSERT_EQ(r.num_ids, 1);
  EXPECT_EQ(r.client_id, "test");
  EXPECT_EQ(r.request_id, request_id_);
  ASSERT_NE(server_.world().Find(r.ids[0]), nullptr);
  EXPECT_DOUBLE_EQ(server_.world().Find(r.ids[0])->x.z(), 1.0);
}

// Verifies that every kind of bad input gets an error reply naming the field
// and leaves the world bit-identical.
TEST_F(SimServerTest, BadInputIsRejectedAndLeavesTheWorldUntouched) {
  ASSERT_EQ(Send(Sphere(0.1, Vec3(0, 0, 1))).code, reply_t::OK);
  const uint64_t before = HashWorldState(server_.world());
  const double nan = std::numeric_limits<double>::quiet_NaN();

  struct Case {
    body_cmd_t cmd;
    int32_t code;
    const char* says;
  };
  std::vector<Case> cases;
  cases.push_back({Sphere(0.1, Vec3(nan, 0, 0)), reply_t::INVALID_ARGUMENT, "position"});
  cases.push_back({Sphere(-1.0, Vec3(0, 0, 0)), reply_t::INVALID_ARGUMENT, "radius"});
  cases.push_back({Sphere(0.0, Vec3(0, 0, 0)), reply_t::INVALID_ARGUMENT, "radius"});
  cases.push_back({Sphere(std::numeric_limits<double>::infinity(), Vec3(0, 0, 0)), reply_t::INVALID_ARGUMENT, "radius"});
  body_cmd_t neg_mass = Sphere(0.1, Vec3::Zero());
  neg_mass.mass = -2.0;
  cases.push_back({neg_mass, reply_t::INVALID_ARGUMENT, "mass"});
  body_cmd_t both = Sphere(0.1, Vec3::Zero());
  both.mass = 1.0;
  both.density = 10.0;
  cases.push_back({both, reply_t::INVALID_ARGUMENT, "mass or density"});
  body_cmd_t bad_e = Sphere(0.1, Vec3::Zero());
  bad_e.has_restitution = true;
  bad_e.restitution = 1.5;
  cases.push_back({bad_e, reply_t::INVALID_ARGUMENT, "restitution"});
  body_cmd_t remove = Sphere(0.1, Vec3::Zero());
  remove.op = body_cmd_t::REMOVE;
  remove.body_id = 42;
  cases.push_back({remove, reply_t::NOT_FOUND, "unknown body id 42"});
  body_cmd_t force = remove;
  force.op = body_cmd_t::APPLY_FORCE;
  cases.push_back({force, reply_t::NOT_FOUND, "unknown body id 42"});
  body_cmd_t bad_op = Sphere(0.1, Vec3::Zero());
  bad_op.op = 99;
  cases.push_back({bad_op, reply_t::INVALID_ARGUMENT, "op"});

  for (Case& c : cases) {
    c.cmd.request_id = ++request_id_;
    const reply_t r = Send(c.cmd);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_EQ(r.request_id, request_id_);
    EXPECT_NE(r.message.find(c.says), std::string::npos) << r.message;
    EXPECT_EQ(HashWorldState(server_.world()), before) << "after: " << r.message;
  }

  scene_cmd_t method = Scene(scene_cmd_t::SET_METHOD);
  method.method = "nosuch";
  reply_t r = Send(method);
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  EXPECT_NE(r.message.find("unknown contact method \"nosuch\""), std::string::npos) << r.message;
  method.method = "impulse";
  method.num_params = 1;
  method.param_names = {"iterations"};
  method.param_values = {"-3"};
  r = Send(method);
  EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT);
  EXPECT_NE(r.message.find("iterations"), std::string::npos) << r.message;

  const uint8_t garbage[] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
  server_.OnMessage(server_.Channel("BODY_CMD"), garbage, sizeof garbage);
  r = transport_.All<reply_t>("T_REPLY").back();
  EXPECT_EQ(r.code, reply_t::DECODE_ERROR);
  EXPECT_EQ(r.request_id, -1);
  EXPECT_EQ(r.client_id, "");
  EXPECT_EQ(HashWorldState(server_.world()), before);
}

// Verifies that STEP n takes n steps, publishes the STATE of the last one
// before the reply, and leaves the server paused.
TEST_F(SimServerTest, StepPublishesTheLastStateBeforeReplying) {
  ASSERT_EQ(Send(Sphere(0.1, Vec3(0, 0, 1))).code, reply_t::OK);
  scene_cmd_t step = Scene(scene_cmd_t::STEP);
  step.steps = 7;
  const auto bytes = Encode(step);
  server_.OnMessage(server_.Channel("SCENE_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  int ticks = 0;
  while (server_.Tick()) ++ticks;
  EXPECT_EQ(ticks, 7);
  EXPECT_EQ(server_.world().step, 7);
  EXPECT_TRUE(server_.paused());
  // the last two messages: STATE of step 7, then the reply
  const auto& msgs = transport_.messages;
  ASSERT_GE(msgs.size(), 2u);
  EXPECT_EQ(msgs[msgs.size() - 2].first, "T_STATE");
  EXPECT_EQ(msgs.back().first, "T_REPLY");
  EXPECT_EQ(transport_.All<state_t>("T_STATE").back().step, 7);
  const reply_t r = transport_.All<reply_t>("T_REPLY").back();
  EXPECT_EQ(r.code, reply_t::OK);
  EXPECT_EQ(r.step, 7);
}

// Verifies that RESET empties the world and restarts the clock but keeps the
// contact method and the paused state.
TEST_F(SimServerTest, ResetKeepsMethodAndPausedState) {
  scene_cmd_t method = Scene(scene_cmd_t::SET_METHOD);
  method.method = "impulse";
  method.num_params = 1;
  method.param_names = {"iterations"};
  method.param_values = {"12"};
  ASSERT_EQ(Send(method).code, reply_t::OK);
  ASSERT_EQ(Send(Sphere(0.1, Vec3(0, 0, 1))).code, reply_t::OK);
  scene_cmd_t g = Scene(scene_cmd_t::SET_GRAVITY);
  g.gravity[2] = -1.0;
  ASSERT_EQ(Send(g).code, reply_t::OK);
  ASSERT_EQ(Send(Scene(scene_cmd_t::RESET)).code, reply_t::OK);
  EXPECT_TRUE(server_.world().bodies().empty());
  EXPECT_EQ(server_.world().step, 0);
  EXPECT_EQ(server_.world().gravity, World::DefaultGravity());
  EXPECT_TRUE(server_.paused());
  EXPECT_EQ(server_.method().Params().at("iterations"), "12");
}

// Verifies that a method switch keeps every body's state bit for bit.
TEST_F(SimServerTest, MethodSwitchKeepsBodyState) {
  body_cmd_t s = Sphere(0.1, Vec3(0, 0, 1));
  s.linear_velocity[0] = 0.3;
  ASSERT_EQ(Send(s).code, reply_t::OK);
  const uint64_t before = HashWorldState(server_.world());
  scene_cmd_t method = Scene(scene_cmd_t::SET_METHOD);
  method.method = "impulse";
  const reply_t r = Send(method);
  EXPECT_EQ(r.code, reply_t::OK);
  EXPECT_NE(r.message.find("contact method impulse"), std::string::npos) << r.message;
  EXPECT_EQ(HashWorldState(server_.world()), before);
}

// Verifies that a switch to the same method with new parameters keeps the
// method's state (penalty's anchors of a sphere resting on the ground, bit
// for bit) and takes the new parameters, while a switch through another
// method starts penalty afresh.
TEST_F(SimServerTest, SwitchToTheSameMethodKeepsItsState) {
  scene_cmd_t method = Scene(scene_cmd_t::SET_METHOD);
  method.method = "penalty";
  ASSERT_EQ(Send(method).code, reply_t::OK);
  body_cmd_t ground = Sphere(0.1, Vec3::Zero());
  ground.shape = body_cmd_t::PLANE;
  ground.plane_normal[2] = 1.0;
  ground.plane_offset = 0.0;
  ASSERT_EQ(Send(ground).code, reply_t::OK);
  ASSERT_EQ(Send(Sphere(0.1, Vec3(0, 0, 0.1))).code, reply_t::OK);
  scene_cmd_t step = Scene(scene_cmd_t::STEP);
  step.steps = 60;
  ASSERT_EQ(Send(step).code, reply_t::OK);
  while (server_.Tick()) {
  }
  const std::string anchors = server_.method().SaveState();
  ASSERT_FALSE(anchors.empty());

  method.request_id = ++request_id_;
  method.num_params = 1;
  method.param_names = {"friction_damping_ratio"};
  method.param_values = {"2"};
  ASSERT_EQ(Send(method).code, reply_t::OK);
  EXPECT_EQ(server_.method().Params().at("friction_damping_ratio"), "2");
  EXPECT_EQ(server_.method().SaveState(), anchors);

  scene_cmd_t other = Scene(scene_cmd_t::SET_METHOD);
  other.method = "impulse";
  ASSERT_EQ(Send(other).code, reply_t::OK);
  method.request_id = ++request_id_;
  ASSERT_EQ(Send(method).code, reply_t::OK);
  EXPECT_NE(server_.method().SaveState(), anchors);
}

}  // namespace
}  // namespace contactsim
