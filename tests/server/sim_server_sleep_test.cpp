// Sleeping through the server (body_commands.cpp, world_commands.cpp):
// on by default, counted in STATUS, and woken by every command that changes
// a sleeping body or what it rests on, so that no command is lost to sleep.
#include <gtest/gtest.h>

#include <contactsim/status_t.hpp>

#include <atomic>
#include <vector>

#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

constexpr double kBoxHalf = 0.1;  // m, the box

// A plane (id 1) and a box resting on it (id 2), stepped 2 s.
void BoxOnPlaneFor2s(ServerHarness& h) {
  body_cmd_t plane = h.Body(body_cmd_t::ADD);
  plane.shape = body_cmd_t::PLANE;
  plane.plane_normal[2] = 1.0;
  ASSERT_EQ(h.Send(plane).code, reply_t::OK);
  ASSERT_EQ(h.Send(h.Box(kBoxHalf, Vec3(0, 0, kBoxHalf + 0.01))).code, reply_t::OK);
  h.Step(480);
}

// The same, asleep by then.
void RestingBox(ServerHarness& h) {
  BoxOnPlaneFor2s(h);
  ASSERT_TRUE(h.server.world().Find(2)->asleep());
}

// Verifies that the server sleeps by default and that STATUS counts the
// sleeping bodies (num_sleeping).
TEST(SimServerSleepTest, SleepsByDefaultAndStatusCountsTheSleepers) {
  EXPECT_TRUE(ServerOptions{}.sleep);
  ServerHarness h{ServerOptions{}};
  RestingBox(h);
  // Run publishes a last STATUS as it stops
  const std::atomic<bool> stop{true};
  h.server.Run(stop);
  const std::vector<status_t> status = h.transport.All<status_t>(h.server.Channel("STATUS"));
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(status.back().num_bodies, 2);
  EXPECT_EQ(status.back().num_sleeping, 1);
}

// Verifies that with `sleep` off nothing sleeps.
TEST(SimServerSleepTest, SleepOffKeepsEveryBodyAwake) {
  ServerOptions o;
  o.sleep = false;
  ServerHarness h(o);
  BoxOnPlaneFor2s(h);
  EXPECT_EQ(h.server.world().SleepingCount(), 0);
  EXPECT_EQ(h.server.world().Find(2)->rest_time, 0.0);
}

// Verifies that SET_VELOCITY, APPLY_IMPULSE and APPLY_FORCE on a sleeping
// box each wake it and take effect at the next step.
TEST(SimServerSleepTest, CommandsOnASleepingBodyWakeItAndAct) {
  ServerHarness h{ServerOptions{}};
  RestingBox(h);
  const Vec3 x0 = h.server.world().Find(2)->x;
  body_cmd_t up = h.Body(body_cmd_t::SET_VELOCITY, 2);
  up.linear_velocity[2] = 1.0;
  ASSERT_EQ(h.Send(up).code, reply_t::OK);
  EXPECT_FALSE(h.server.world().Find(2)->asleep());
  h.Step(1);
  EXPECT_GT(h.server.world().Find(2)->x.z(), x0.z() + 0.003);  // 1 m/s for 1/240 s

  h.Step(480);
  ASSERT_TRUE(h.server.world().Find(2)->asleep());
  const double m = h.server.world().Find(2)->mass;
  body_cmd_t kick = h.Body(body_cmd_t::APPLY_IMPULSE, 2);
  kick.impulse[2] = m;  // 1 m/s up
  ASSERT_EQ(h.Send(kick).code, reply_t::OK);
  h.Step(1);
  EXPECT_GT(h.server.world().Find(2)->LinearVelocity().z(), 0.9);

  h.Step(480);
  ASSERT_TRUE(h.server.world().Find(2)->asleep());
  body_cmd_t lift = h.Body(body_cmd_t::APPLY_FORCE, 2);
  lift.force[2] = 3 * m * 9.81;
  lift.duration = 0.1;
  ASSERT_EQ(h.Send(lift).code, reply_t::OK);
  h.Step(24);
  EXPECT_GT(h.server.world().Find(2)->x.z(), h.server.world().Find(1)->x.z() + kBoxHalf + 0.05);
}

// Verifies that removing the plane under a sleeping box wakes it (it falls),
// and that a gravity change wakes every body.
TEST(SimServerSleepTest, RemovingTheSupportAndChangingGravityWake) {
  ServerHarness h{ServerOptions{}};
  RestingBox(h);
  scene_cmd_t g = h.Scene(scene_cmd_t::SET_GRAVITY);
  g.gravity[0] = 3.0;
  g.gravity[2] = -9.81;
  ASSERT_EQ(h.Send(g).code, reply_t::OK);
  EXPECT_EQ(h.server.world().SleepingCount(), 0);
  g.gravity[0] = 0.0;
  ASSERT_EQ(h.Send(g).code, reply_t::OK);
  h.Step(480);
  ASSERT_TRUE(h.server.world().Find(2)->asleep());
  const double z0 = h.server.world().Find(2)->x.z();
  ASSERT_EQ(h.Send(h.Body(body_cmd_t::REMOVE, 1)).code, reply_t::OK);
  EXPECT_FALSE(h.server.world().Find(2)->asleep());
  h.Step(24);
  EXPECT_LT(h.server.world().Find(2)->x.z(), z0 - 0.02);  // g t^2 / 2 = 0.049 m
}

}  // namespace
}  // namespace contactsim
