// Islands (service/contact/sleep/islands.h): who joins whom.
#include "service/contact/sleep/islands.h"

#include <gtest/gtest.h>

#include <vector>

#include "tests/contact/joint_test_util.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;

constexpr double kHalf = 0.1;  // m

// Verifies that two stacks on one ground are two islands (the ground joins
// none), and that a contact or a joint between dynamic bodies joins them.
TEST(IslandsTest, StaticBodiesJoinNoIsland) {
  World world;
  AddGround(world, 0.0, 0.5);
  const BodyId a = AddBox(world, kHalf, Vec3(0, 0, kHalf), 0.0, 0.5);
  const BodyId b = AddBox(world, kHalf, Vec3(1, 0, kHalf), 0.0, 0.5);
  const BodyId c = AddBox(world, kHalf, Vec3(1, 0, 3 * kHalf), 0.0, 0.5);
  ContactSet contacts(3);
  contacts[0].a = 0, contacts[0].b = world.IndexOf(a);
  contacts[1].a = 0, contacts[1].b = world.IndexOf(b);
  contacts[2].a = world.IndexOf(b), contacts[2].b = world.IndexOf(c);
  std::vector<int> root = FindIslands(world, contacts, {});
  EXPECT_EQ(root[0], -1);
  EXPECT_EQ(root[world.IndexOf(a)], world.IndexOf(a));
  EXPECT_EQ(root[world.IndexOf(c)], world.IndexOf(b));
  testing::AddJoint(world, JointKind::kBall, a, c, Vec3(0.5, 0, kHalf));
  root = FindIslands(world, contacts, {});
  EXPECT_EQ(root[world.IndexOf(b)], world.IndexOf(a));
  EXPECT_EQ(root[world.IndexOf(c)], world.IndexOf(a));
}

// Verifies that a near pair (overlapping wake boxes) joins two bodies, and
// that a sleeping body joins no island.
TEST(IslandsTest, NearPairsJoinAndSleepersStayOut) {
  World world;
  const BodyId a = AddBox(world, kHalf, Vec3(0, 0, 1), 0.0, 0.5);
  const BodyId b = AddBox(world, kHalf, Vec3(0.25, 0, 1), 0.0, 0.5);
  std::vector<int> root = FindIslands(world, {}, {{world.IndexOf(a), world.IndexOf(b)}});
  EXPECT_EQ(root[world.IndexOf(b)], world.IndexOf(a));
  world.Find(b)->sleep_island = b;
  root = FindIslands(world, {}, {{world.IndexOf(a), world.IndexOf(b)}});
  EXPECT_EQ(root[world.IndexOf(a)], world.IndexOf(a));
  EXPECT_EQ(root[world.IndexOf(b)], -1);
}

}  // namespace
}  // namespace contactsim
