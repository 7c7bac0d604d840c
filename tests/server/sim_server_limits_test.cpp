// Tests of the server's limits: each is refused with RESOURCE_EXHAUSTED and
// a message naming it, counted in STATUS, and leaves the world as it was.
#include <gtest/gtest.h>

#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/status_t.hpp>

#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

ServerOptions Limited() {
  ServerOptions o;
  o.prefix = "L";
  o.max_bodies = 3;
  o.max_joints = 1;
  return o;
}

joint_cmd_t Ball(int64_t a) {
  joint_cmd_t m{};
  m.client_id = "test";
  m.op = joint_cmd_t::ADD;
  m.kind = joint_cmd_t::BALL;
  m.body_a = a;
  m.anchor[2] = 2.0;
  return m;
}

reply_t SendJoint(ServerHarness& h, joint_cmd_t m) {
  m.request_id = ++h.request_id;
  const auto bytes = testing::Encode(m);
  h.server.OnMessage(h.server.Channel("JOINT_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  h.server.Tick();
  return h.transport.All<reply_t>(h.server.Channel("REPLY")).back();
}

// Verifies that bodies and joints beyond their limits are refused by name
// and change nothing.
TEST(SimServerLimitsTest, BodiesAndJointsBeyondTheirLimits) {
  ServerHarness h(Limited());
  for (int i = 0; i < 3; ++i) ASSERT_EQ(h.Send(h.Box(0.1, Vec3(i, 0, 1))).code, reply_t::OK);
  const uint64_t before = HashWorldState(h.server.world());
  reply_t r = h.Send(h.Box(0.1, Vec3(5, 0, 1)));
  EXPECT_EQ(r.code, reply_t::RESOURCE_EXHAUSTED);
  EXPECT_NE(r.message.find("max_bodies = 3"), std::string::npos) << r.message;
  EXPECT_EQ(HashWorldState(h.server.world()), before);
  ASSERT_EQ(SendJoint(h, Ball(1)).code, reply_t::OK);
  r = SendJoint(h, Ball(2));
  EXPECT_EQ(r.code, reply_t::RESOURCE_EXHAUSTED);
  EXPECT_NE(r.message.find("max_joints = 1"), std::string::npos) << r.message;
  EXPECT_EQ(h.server.world().joints().size(), 1u);
}

// Verifies that a client beyond its burst is refused at once (before the
// inbox) while another client is still served, and that STATUS counts it.
TEST(SimServerLimitsTest, AClientBeyondItsRateIsRefusedAndOthersAreNot) {
  ServerOptions o;
  o.prefix = "L";
  o.max_commands_per_second = 1e-3;  // nothing refills during the test
  o.command_burst = 5;
  ServerHarness h(o);
  for (int i = 0; i < 8; ++i) {
    body_cmd_t m = h.Box(0.1, Vec3(i, 0, 1));
    m.client_id = "flood";
    h.Post(m);
  }
  body_cmd_t polite = h.Box(0.1, Vec3(0, 5, 1));
  polite.client_id = "polite";
  h.Post(polite);
  h.server.Tick();
  int ok = 0, limited = 0;
  for (const reply_t& r : h.transport.All<reply_t>(h.server.Channel("REPLY"))) {
    if (r.client_id == "polite") {
      EXPECT_EQ(r.code, reply_t::OK);
    }
    ok += r.code == reply_t::OK;
    if (r.code == reply_t::RESOURCE_EXHAUSTED) {
      ++limited;
      EXPECT_EQ(r.client_id, "flood");
      EXPECT_NE(r.message.find("max_commands_per_second"), std::string::npos) << r.message;
    }
  }
  EXPECT_EQ(ok, 6);
  EXPECT_EQ(limited, 3);
  EXPECT_EQ(h.server.world().bodies().size(), 6u);
}

// Verifies that the inbox is bounded: commands beyond max_queued_commands
// are answered at once and never reach the world.
TEST(SimServerLimitsTest, TheInboxIsBounded) {
  ServerOptions o;
  o.prefix = "L";
  o.max_queued_commands = 4;
  ServerHarness h(o);
  for (int i = 0; i < 6; ++i) {
    body_cmd_t m = h.Box(0.1, Vec3(i, 0, 1));
    h.Post(m);
  }
  auto replies = h.transport.All<reply_t>(h.server.Channel("REPLY"));
  ASSERT_EQ(replies.size(), 2u);
  for (const reply_t& r : replies) {
    EXPECT_EQ(r.code, reply_t::RESOURCE_EXHAUSTED);
    EXPECT_NE(r.message.find("max_queued_commands = 4"), std::string::npos) << r.message;
  }
  h.server.Tick();
  EXPECT_EQ(h.server.world().bodies().size(), 4u);
}

// Verifies that SET_POSE refuses the zero quaternion (on ADD it means "not
// given", the identity) and keeps the pose.
TEST(SimServerLimitsTest, SetPoseRefusesTheZeroQuaternion) {
  ServerHarness h(Limited());
  body_cmd_t add = h.Box(0.1, Vec3(0, 0, 1));
  add.orientation[0] = 0.0;
  ASSERT_EQ(h.Send(add).code, reply_t::OK);
  EXPECT_EQ(h.server.world().bodies()[0].q.coeffs(), Quat::Identity().coeffs());
  body_cmd_t pose = h.Body(body_cmd_t::SET_POSE, 1);
  pose.orientation[0] = 0.0;
  pose.position[2] = 3.0;
  const reply_t r = h.Send(pose);
  EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT);
  EXPECT_NE(r.message.find("orientation must be a unit quaternion"), std::string::npos) << r.message;
  EXPECT_EQ(h.server.world().bodies()[0].x.z(), 1.0);
}

}  // namespace
}  // namespace contactsim
