// Tests of the world's mimics (physics/joint.h JointMimic,
// World::SetJointMimic): what is refused, and that nothing changes then;
// the hash; a removed master takes the mimic with it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "service/physics/body_settings.h"
#include "service/physics/joint.h"
#include "service/physics/world.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

JointId Add(World& world, JointKind kind, BodyId a, const Vec3& at) {
  JointSettings s;
  s.kind = kind;
  s.body_a = a;
  s.anchor = at;
  if (HasJointCoordinate(kind)) s.axis = Vec3::UnitX();
  JointId id = 0;
  const Status st = world.AddJoint(s, &id);
  EXPECT_TRUE(st.ok()) << st.message();
  return id;
}

struct Hand {
  World world;
  JointId h1 = 0, h2 = 0, h3 = 0, slider = 0, ball = 0;
  Hand() {
    h1 = Add(world, JointKind::kHinge, testing::AddSphere(world, 0.1, Vec3(0, 0, 0), 0.5), Vec3(0, 0, 0));
    h2 = Add(world, JointKind::kHinge, testing::AddSphere(world, 0.1, Vec3(1, 0, 0), 0.5), Vec3(1, 0, 0));
    h3 = Add(world, JointKind::kHinge, testing::AddSphere(world, 0.1, Vec3(2, 0, 0), 0.5), Vec3(2, 0, 0));
    slider = Add(world, JointKind::kPrismatic, testing::AddSphere(world, 0.1, Vec3(3, 0, 0), 0.5), Vec3(3, 0, 0));
    ball = Add(world, JointKind::kBall, testing::AddSphere(world, 0.1, Vec3(4, 0, 0), 0.5), Vec3(4, 0, 0));
  }
};

// The message of a refused SetJointMimic; the world's hash is unchanged.
std::string Refused(World& world, JointId follower, const JointMimic& mimic) {
  const uint64_t before = HashWorldState(world);
  const Status st = world.SetJointMimic(follower, mimic);
  EXPECT_FALSE(st.ok());
  EXPECT_EQ(HashWorldState(world), before);
  return st.message();
}

// Verifies each refusal: an unknown follower or master, the joint itself,
// a cycle, joints of different kinds or without a coordinate, a
// non-finite multiplier or offset.
TEST(JointMimicTest, BadMimicsAreRefusedAndNothingChanges) {
  Hand h;
  EXPECT_EQ(h.world.SetJointMimic(99, JointMimic{h.h1}).code(), StatusCode::kNotFound);
  EXPECT_NE(Refused(h.world, h.h2, JointMimic{99}).find("does not exist"), std::string::npos);
  EXPECT_NE(Refused(h.world, h.h2, JointMimic{h.h2}).find("cannot mimic itself"), std::string::npos);
  EXPECT_NE(Refused(h.world, h.h2, JointMimic{h.slider}).find("hinge) cannot mimic joint"), std::string::npos);
  EXPECT_NE(Refused(h.world, h.ball, JointMimic{h.h1}).find("two hinges or two prismatic"), std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(Refused(h.world, h.h2, JointMimic{h.h1, nan, 0.0}).find("finite"), std::string::npos);
  EXPECT_NE(Refused(h.world, h.h2, JointMimic{h.h1, 1.0, INFINITY}).find("finite"), std::string::npos);
  ASSERT_TRUE(h.world.SetJointMimic(h.h2, JointMimic{h.h1}).ok());
  ASSERT_TRUE(h.world.SetJointMimic(h.h3, JointMimic{h.h2}).ok());
  EXPECT_NE(Refused(h.world, h.h1, JointMimic{h.h3}).find("cycle"), std::string::npos);
}

// Verifies that a mimic changes the hash (it changes the motion), that
// master 0 removes it, and that removing the master removes the mimic.
TEST(JointMimicTest, HashAndRemoval) {
  Hand h;
  const uint64_t plain = HashWorldState(h.world);
  ASSERT_TRUE(h.world.SetJointMimic(h.h2, JointMimic{h.h1, -1.0, 0.1}).ok());
  EXPECT_NE(HashWorldState(h.world), plain);
  EXPECT_TRUE(h.world.HasJointMimics());
  ASSERT_TRUE(h.world.SetJointMimic(h.h2, JointMimic{}).ok());
  EXPECT_EQ(HashWorldState(h.world), plain);
  ASSERT_TRUE(h.world.SetJointMimic(h.h2, JointMimic{h.h1, 2.0, 0.0}).ok());
  ASSERT_TRUE(h.world.RemoveJoint(h.h1).ok());
  EXPECT_FALSE(h.world.HasJointMimics());
  EXPECT_EQ(h.world.FindJoint(h.h2)->mimic.master, 0);
}

}  // namespace
}  // namespace contactsim
