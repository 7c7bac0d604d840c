// Tests of the collision filter through the server (body_cmd_t ADD with
// has_filter, SET_FILTER; joint_cmd_t collide_connected): a filter set at
// runtime drops the top of a sleeping stack through the box below it; a
// server recovered from its journal folder (snapshots taken while the top
// falls, then the records after them) keeps every filter and continues bit
// for bit; SET_FILTER on an unknown body or on the world is refused and
// changes nothing.
#include <gtest/gtest.h>

#include "tests/server/server_harness.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

using testing::ServerHarness;
using testing::TempDir;

constexpr double kHalf = 0.1;  // m, the boxes

body_cmd_t Filter(ServerHarness& h, BodyId id, uint32_t category, uint32_t mask, int32_t group) {
  body_cmd_t m = h.Body(body_cmd_t::SET_FILTER, id);
  m.collision_category = static_cast<int32_t>(category);  // the wire's bit pattern
  m.collision_mask = static_cast<int32_t>(mask);
  m.collision_group = group;
  return m;
}

// Ground (1), a lower box of category 2 (2), an upper box resting on it
// (3), and two spheres on a ball joint that lets them touch (4, 5); 120
// steps; the upper box's mask set to the ground's category; 30 steps more.
void DriveFilteredPairs(ServerHarness& h) {
  body_cmd_t ground = h.Body(body_cmd_t::ADD);
  ground.shape = body_cmd_t::PLANE;
  ground.plane_normal[2] = 1.0;
  ASSERT_EQ(h.Send(ground).code, reply_t::OK);
  body_cmd_t lower = h.Box(kHalf, Vec3(0, 0, kHalf + 1e-3));
  lower.has_restitution = false;
  lower.has_filter = true;
  lower.collision_category = 2;
  lower.collision_mask = -1;  // every bit
  ASSERT_EQ(h.Send(lower).code, reply_t::OK);
  body_cmd_t upper = h.Box(kHalf, Vec3(0, 0, 3 * kHalf + 2e-3));
  upper.has_restitution = false;
  ASSERT_EQ(h.Send(upper).code, reply_t::OK);
  for (double x : {1.0, 1.2}) {  // touching at x = 1.1
    body_cmd_t s = h.Body(body_cmd_t::ADD);
    s.shape = body_cmd_t::SPHERE;
    s.radius = 0.1;
    s.position[0] = x;
    s.position[2] = 1.0;
    ASSERT_EQ(h.Send(s).code, reply_t::OK);
  }
  joint_cmd_t j{};
  j.client_id = "test";
  j.op = joint_cmd_t::ADD;
  j.kind = joint_cmd_t::BALL;
  j.body_a = 4;
  j.body_b = 5;
  j.anchor[0] = 1.1;
  j.anchor[2] = 1.0;
  j.collide_connected = true;
  ASSERT_EQ(h.Send(j).code, reply_t::OK);
  h.Step(120);
  const reply_t r = h.Send(Filter(h, 3, 1u, 1u, 0));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(r.message, "collision filter of body 3 set");
  h.Step(30);
}

// Verifies that ADD carries the filter, the joint its collide_connected,
// and that SET_FILTER drops the resting (sleeping) top box through the
// lower one onto the ground.
TEST(SimServerFilterTest, SetFilterDropsTheTopOfASleepingStack) {
  ServerOptions options;
  options.sleep = true;
  ServerHarness h(options);
  DriveFilteredPairs(h);
  const World& w = h.server.world();
  EXPECT_EQ(w.Find(2)->collision_category, 2u);
  EXPECT_EQ(w.Find(2)->collision_mask, 0xFFFFFFFFu);
  EXPECT_EQ(w.Find(3)->collision_mask, 1u);
  EXPECT_TRUE(w.FindJoint(1)->collide_connected);
  EXPECT_FALSE(w.joined_pairs().Contains(4, 5));
  h.Step(210);
  EXPECT_NEAR(w.Find(3)->x.z(), kHalf, 0.01) << "the top box fell through onto the ground";
  EXPECT_NEAR(w.Find(2)->x.z(), kHalf, 0.01);
}

// Verifies that the stack slept before the filter changed and that
// SET_FILTER woke it (the reply is the change's, the next step moves it).
TEST(SimServerFilterTest, SetFilterWakesASleepingStack) {
  ServerOptions options;
  options.sleep = true;
  ServerHarness h(options);
  body_cmd_t ground = h.Body(body_cmd_t::ADD);
  ground.shape = body_cmd_t::PLANE;
  ground.plane_normal[2] = 1.0;
  ASSERT_EQ(h.Send(ground).code, reply_t::OK);
  body_cmd_t lower = h.Box(kHalf, Vec3(0, 0, kHalf + 1e-3));
  lower.has_restitution = false;
  lower.has_filter = true;
  lower.collision_category = 2;
  lower.collision_mask = -1;
  ASSERT_EQ(h.Send(lower).code, reply_t::OK);
  body_cmd_t upper = h.Box(kHalf, Vec3(0, 0, 3 * kHalf + 2e-3));
  upper.has_restitution = false;
  ASSERT_EQ(h.Send(upper).code, reply_t::OK);
  h.Step(480);
  ASSERT_TRUE(h.server.world().Find(3)->asleep());
  ASSERT_EQ(h.Send(Filter(h, 3, 1u, 1u, 0)).code, reply_t::OK);
  EXPECT_FALSE(h.server.world().Find(3)->asleep());
  EXPECT_FALSE(h.server.world().Find(2)->asleep());
  h.Step(240);
  EXPECT_NEAR(h.server.world().Find(3)->x.z(), kHalf, 0.01);
}

// Verifies that a server restarted on its journal folder (a snapshot every
// 50 steps, the last one while the top box is inside the lower one) comes
// back with the filters and the joint's flag and continues as a server
// that never stopped.
TEST(SimServerFilterTest, JournalRecoveryKeepsTheFilters) {
  TempDir dir;
  ServerOptions options;
  options.prefix = "F";
  options.snapshot_every = 50;
  ServerHarness reference(options);
  DriveFilteredPairs(reference);
  options.journal_dir = dir.path();
  {
    ServerHarness first(options);
    DriveFilteredPairs(first);
    ASSERT_EQ(HashWorldState(first.server.world()), HashWorldState(reference.server.world()));
  }
  ServerHarness recovered(options);
  const World& w = recovered.server.world();
  EXPECT_EQ(w.step, 150);
  EXPECT_EQ(w.Find(2)->collision_category, 2u);
  EXPECT_EQ(w.Find(3)->collision_mask, 1u);
  ASSERT_NE(w.FindJoint(1), nullptr);
  EXPECT_TRUE(w.FindJoint(1)->collide_connected);
  EXPECT_EQ(HashWorldState(w), HashWorldState(reference.server.world()));
  EXPECT_EQ(recovered.Step(60), reference.Step(60));
}

// Verifies that SET_FILTER on an unknown body and on the world (id 0) is
// NOT_FOUND naming it, and leaves every body's filter and the world as
// they were; and that every bit pattern is a filter (mask and category 0
// included).
TEST(SimServerFilterTest, SetFilterOnAnUnknownBodyOrTheWorldChangesNothing) {
  ServerHarness h(ServerOptions{});
  ASSERT_EQ(h.Send(h.Box(kHalf, Vec3(0, 0, 1))).code, reply_t::OK);
  const uint64_t before = HashWorldState(h.server.world());
  reply_t r = h.Send(Filter(h, 99, 2u, 2u, 1));
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  EXPECT_EQ(r.message, "unknown body id 99");
  r = h.Send(Filter(h, 0, 2u, 2u, 1));
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  EXPECT_EQ(r.message, "body id 0 is the world, which has no collision filter");
  EXPECT_EQ(HashWorldState(h.server.world()), before);
  const RigidBody& b = *h.server.world().Find(1);
  EXPECT_EQ(b.collision_category, 1u);
  EXPECT_EQ(b.collision_mask, 0xFFFFFFFFu);
  EXPECT_EQ(b.collision_group, 0);
  EXPECT_EQ(h.Send(Filter(h, 1, 0u, 0u, INT32_MIN)).code, reply_t::OK);
  EXPECT_EQ(b.collision_category, 0u);
  EXPECT_EQ(b.collision_group, INT32_MIN);
}

}  // namespace
}  // namespace contactsim
