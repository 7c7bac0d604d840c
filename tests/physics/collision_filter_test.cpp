// The collision filter's predicate (service/physics/collision_filter.h)
// against Box2D's rule written out independently here, over the whole group
// table and random 32-bit categories and masks, and the world's set of
// joint-excluded pairs kept in step with its joints.
#include "service/physics/collision_filter.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

#include "service/physics/body_settings.h"
#include "service/physics/world.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

RigidBody Filtered(BodyId id, uint32_t category, uint32_t mask, int32_t group) {
  RigidBody b;
  b.id = id;
  b.collision_category = category;
  b.collision_mask = mask;
  b.collision_group = group;
  return b;
}

// Box2D's b2ContactFilter::ShouldCollide (b2_world_callbacks.cpp), as given.
bool Box2dRule(uint32_t cat_a, uint32_t mask_a, int32_t group_a, uint32_t cat_b, uint32_t mask_b, int32_t group_b) {
  if (group_a == group_b && group_a != 0) return group_a > 0;
  return (mask_a & cat_b) != 0 && (mask_b & cat_a) != 0;
}

TEST(CollisionFilterTest, DefaultBodiesTouchEachOther) {
  const RigidBody a, b;
  EXPECT_TRUE(HasDefaultFilter(a));
  EXPECT_TRUE(ShouldCollide(a, b, JointPairSet()));
}

// Every combination of the groups (none, same, different; positive and
// negative) with masks that accept and masks that refuse each other.
TEST(CollisionFilterTest, GroupTableIsBox2ds) {
  struct Row {
    int32_t group_a, group_b;
    bool if_masks_accept, if_masks_refuse;
  };
  const Row rows[] = {
      {0, 0, true, false},     // no group: the masks decide
      {3, 3, true, true},      // same positive group: always
      {-3, -3, false, false},  // same negative group: never
      {3, 4, true, false},     // different groups: the masks decide
      {-3, -4, true, false},
      {3, -3, true, false},
      {0, 3, true, false},
      {0, -3, true, false},
      {-3, 0, true, false},
  };
  for (const Row& r : rows) {
    for (bool accept : {true, false}) {
      // A is category 2; B's mask takes 2 or not, B is category 1 and A's mask takes 1
      const RigidBody a = Filtered(1, 2u, 1u, r.group_a);
      const RigidBody b = Filtered(2, 1u, accept ? 0xFFFFFFFFu : ~2u, r.group_b);
      const bool expected = accept ? r.if_masks_accept : r.if_masks_refuse;
      EXPECT_EQ(ShouldCollide(a, b, JointPairSet()), expected) << r.group_a << " " << r.group_b << " " << accept;
      EXPECT_EQ(ShouldCollide(b, a, JointPairSet()), expected) << "symmetric";
    }
  }
}

// 200000 random filters, groups drawn from a small set so that equal groups
// occur often: the predicate is Box2D's and symmetric.
TEST(CollisionFilterTest, RandomCategoriesAndMasksFollowBox2dsRule) {
  std::mt19937_64 rng(41);
  std::uniform_int_distribution<uint32_t> bits;
  std::uniform_int_distribution<int32_t> group(-2, 2);
  int accepted = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    // sparse masks too, so that both answers are frequent
    const uint32_t sparse = i % 2 == 0 ? 0xFFFFFFFFu : bits(rng);
    const RigidBody a = Filtered(1, bits(rng) & sparse, bits(rng) & bits(rng), group(rng));
    const RigidBody b = Filtered(2, bits(rng) & sparse, bits(rng) & bits(rng), group(rng));
    const bool expected = Box2dRule(a.collision_category, a.collision_mask, a.collision_group, b.collision_category,
                                    b.collision_mask, b.collision_group);
    ASSERT_EQ(ShouldCollide(a, b, JointPairSet()), expected) << i;
    ASSERT_EQ(ShouldCollide(b, a, JointPairSet()), expected) << i;
    accepted += expected ? 1 : 0;
  }
  EXPECT_GT(accepted, n / 10);
  EXPECT_LT(accepted, n - n / 10);
}

// A joint-excluded pair never touches, even in one positive group.
TEST(CollisionFilterTest, JointExclusionWinsOverAPositiveGroup) {
  JointPairSet joined;
  joined.Add(7, 3);
  const RigidBody a = Filtered(3, 1u, 0xFFFFFFFFu, 5), b = Filtered(7, 1u, 0xFFFFFFFFu, 5);
  EXPECT_FALSE(ShouldCollide(a, b, joined));
  EXPECT_FALSE(ShouldCollide(b, a, joined));
  joined.Remove(3, 7);
  EXPECT_TRUE(ShouldCollide(a, b, joined));
}

TEST(CollisionFilterTest, JointPairSetCountsJointsPerPair) {
  JointPairSet s;
  s.Add(1, 2);
  s.Add(2, 1);
  EXPECT_EQ(s.size(), 1u);
  s.Remove(1, 2);
  EXPECT_TRUE(s.Contains(2, 1));
  s.Remove(2, 1);
  EXPECT_FALSE(s.Contains(1, 2));
  EXPECT_TRUE(s.empty());
  s.Remove(1, 2);  // absent: nothing happens
  EXPECT_TRUE(s.empty());
}

JointId AddBallJoint(World& world, BodyId a, BodyId b, bool collide_connected) {
  JointSettings s;
  s.kind = JointKind::kBall;
  s.body_a = a;
  s.body_b = b;
  s.anchor = Vec3(0, 0, 1);
  s.collide_connected = collide_connected;
  JointId id = 0;
  EXPECT_TRUE(world.AddJoint(s, &id).ok());
  return id;
}

// The excluded pairs follow every way joints come and go.
TEST(CollisionFilterTest, WorldKeepsJointPairsInStepWithItsJoints) {
  World world;
  const BodyId a = testing::AddSphere(world, 0.1, Vec3(0, 0, 1), 0.5);
  const BodyId b = testing::AddSphere(world, 0.1, Vec3(0, 0, 1.1), 0.5);
  const BodyId c = testing::AddSphere(world, 0.1, Vec3(0, 0, 1.2), 0.5);
  const JointId ab = AddBallJoint(world, a, b, false);
  const JointId ab2 = AddBallJoint(world, b, a, false);
  AddBallJoint(world, b, c, true);  // touching allowed: not excluded
  AddBallJoint(world, c, kWorldBody, false);  // the world has no contacts to exclude
  const JointPairSet& joined = world.joined_pairs();
  EXPECT_TRUE(joined.Contains(a, b));
  EXPECT_FALSE(joined.Contains(b, c));
  EXPECT_EQ(joined.size(), 1u);
  ASSERT_TRUE(world.RemoveJoint(ab).ok());
  EXPECT_TRUE(joined.Contains(a, b)) << "the second joint still holds them";
  ASSERT_TRUE(world.RemoveJoint(ab2).ok());
  EXPECT_FALSE(joined.Contains(a, b));
  AddBallJoint(world, a, b, false);
  // a snapshot's joints, put back
  const std::vector<Joint> saved = world.joints();
  ASSERT_TRUE(world.AssignJoints({}, world.next_joint_id).ok());
  EXPECT_TRUE(joined.empty());
  ASSERT_TRUE(world.AssignJoints(saved, world.next_joint_id).ok());
  EXPECT_TRUE(joined.Contains(b, a));
  ASSERT_TRUE(world.RemoveBody(a).ok());  // takes its joints
  EXPECT_TRUE(joined.empty());
  AddBallJoint(world, b, c, false);
  world.Clear();
  EXPECT_TRUE(world.joined_pairs().empty());
}

TEST(CollisionFilterTest, SetCollisionFilterChangesTheBodyAndWakesIt) {
  World world;
  world.sleep.enabled = true;
  const BodyId a = testing::AddSphere(world, 0.1, Vec3(0, 0, 1), 0.5);
  world.Find(a)->sleep_island = a;
  world.Find(a)->rest_time = 2.0;
  ASSERT_TRUE(world.SetCollisionFilter(a, 4u, 0x0Fu, -2).ok());
  const RigidBody& b = *world.Find(a);
  EXPECT_EQ(b.collision_category, 4u);
  EXPECT_EQ(b.collision_mask, 0x0Fu);
  EXPECT_EQ(b.collision_group, -2);
  EXPECT_FALSE(b.asleep());
  EXPECT_EQ(b.rest_time, 0.0);
}

TEST(CollisionFilterTest, SetCollisionFilterRefusesUnknownBodiesAndTheWorld) {
  World world;
  const BodyId a = testing::AddSphere(world, 0.1, Vec3(0, 0, 1), 0.5);
  const uint64_t before = HashWorldState(world);
  for (BodyId id : {BodyId{0}, BodyId{99}, BodyId{-1}}) {
    const Status st = world.SetCollisionFilter(id, 2u, 2u, 1);
    EXPECT_EQ(st.code(), StatusCode::kNotFound) << id;
    EXPECT_NE(st.message().find(id == 0 ? "world" : "unknown body id"), std::string::npos) << st.message();
  }
  EXPECT_TRUE(HasDefaultFilter(*world.Find(a)));
  EXPECT_EQ(HashWorldState(world), before);
}

TEST(CollisionFilterTest, CreateBodyAndCreateJointCarryTheFilter) {
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = 0.1;
  s.collision_category = 8u;
  s.collision_mask = 0xF0u;
  s.collision_group = -7;
  RigidBody b;
  ASSERT_TRUE(CreateBody(s, Material{}, &b).ok());
  EXPECT_EQ(b.collision_category, 8u);
  EXPECT_EQ(b.collision_mask, 0xF0u);
  EXPECT_EQ(b.collision_group, -7);
  World world;
  const BodyId x = testing::AddSphere(world, 0.1, Vec3(0, 0, 1), 0.5), y = testing::AddSphere(world, 0.1, Vec3(0, 0, 1.1), 0.5);
  const JointId j = AddBallJoint(world, x, y, true);
  EXPECT_TRUE(world.FindJoint(j)->collide_connected);
  EXPECT_FALSE(JointSettings().collide_connected) << "joined bodies do not touch by default";
}

}  // namespace
}  // namespace contactsim
