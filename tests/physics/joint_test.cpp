// Tests of joint creation and validation (physics/joint.h) and the world's
// joint bookkeeping (world.h).
#include "service/physics/joint.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "service/physics/body_settings.h"
#include "service/physics/world.h"

namespace contactsim {
namespace {

BodyId AddSphere(World& world, const Vec3& p, bool fixed = false) {
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = 0.1;
  s.position = p;
  s.fixed = fixed;
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  return world.AddBody(b);
}

JointSettings Ball(BodyId a, BodyId b, const Vec3& anchor) {
  JointSettings s;
  s.kind = JointKind::kBall;
  s.body_a = a;
  s.body_b = b;
  s.anchor = anchor;
  return s;
}

// Adds a joint that must be rejected and checks the message and that the
// world (hash and joint count) did not change.
std::string Rejected(World& world, const JointSettings& s) {
  const uint64_t before = HashWorldState(world);
  const size_t count = world.joints().size();
  JointId id = -1;
  const Status st = world.AddJoint(s, &id);
  EXPECT_FALSE(st.ok());
  EXPECT_EQ(id, -1);
  EXPECT_EQ(HashWorldState(world), before);
  EXPECT_EQ(world.joints().size(), count);
  return st.message();
}

// Verifies that anchors and axes are stored in the bodies' frames, so that
// they read back as the world values given at creation.
TEST(JointTest, StoresAnchorsAndAxesInBodyFrames) {
  World world;
  const BodyId a = AddSphere(world, Vec3(1, 0, 0));
  const BodyId b = AddSphere(world, Vec3(0, 2, 0));
  world.Find(b)->q = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  JointSettings s = Ball(a, b, Vec3(0.5, 1, 0.25));
  s.kind = JointKind::kHinge;
  s.axis = Vec3(0, 0, 2);
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(s, &id).ok());
  const Joint& j = *world.FindJoint(id);
  EXPECT_TRUE(AnchorWorld(j.anchor_a, world.Find(a)).isApprox(s.anchor, 1e-14));
  EXPECT_TRUE(AnchorWorld(j.anchor_b, world.Find(b)).isApprox(s.anchor, 1e-14));
  EXPECT_TRUE((world.Find(a)->q * j.axis_a).isApprox(Vec3::UnitZ(), 1e-14));
  EXPECT_TRUE((world.Find(b)->q * j.axis_b).isApprox(Vec3::UnitZ(), 1e-14));
  EXPECT_NEAR(HingeAngle(j, *world.Find(a), world.Find(b)), 0.0, 1e-14);
}

// Verifies that a distance joint's default length is the current distance
// from body_a's centre of mass to the anchor.
TEST(JointTest, DistanceDefaultsToTheCurrentLength) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 1));
  JointSettings s = Ball(a, kWorldBody, Vec3(0, 0, 3.5));
  s.kind = JointKind::kDistance;
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(s, &id).ok());
  EXPECT_DOUBLE_EQ(world.FindJoint(id)->length, 2.5);
  EXPECT_TRUE(world.FindJoint(id)->anchor_a.isZero());
}

// Verifies that the hinge angle measures B's rotation about the axis since
// creation, right-handed, for a turn of B and an opposite turn of A.
TEST(JointTest, HingeAngleFollowsTheRelativeRotation) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 0));
  const BodyId b = AddSphere(world, Vec3(1, 0, 0));
  JointSettings s = Ball(a, b, Vec3(0.5, 0, 0));
  s.kind = JointKind::kHinge;
  s.axis = Vec3(0, 1, 0);
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(s, &id).ok());
  const Joint& j = *world.FindJoint(id);
  world.Find(b)->q = Quat(Eigen::AngleAxisd(0.4, Vec3::UnitY()));
  EXPECT_NEAR(HingeAngle(j, *world.Find(a), world.Find(b)), 0.4, 1e-14);
  world.Find(a)->q = Quat(Eigen::AngleAxisd(0.5, Vec3::UnitY()));
  EXPECT_NEAR(HingeAngle(j, *world.Find(a), world.Find(b)), -0.1, 1e-14);
}

// Verifies that bad settings are refused with a message naming the field
// and the value, and leave the world unchanged.
TEST(JointTest, RejectsBadSettingsAndLeavesTheWorldUnchanged) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 1));
  const BodyId wall = AddSphere(world, Vec3(0, 0, 3), /*fixed=*/true);
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(Ball(a, kWorldBody, Vec3(0, 0, 2)), &id).ok());
  const double nan = std::numeric_limits<double>::quiet_NaN();

  EXPECT_EQ(Rejected(world, Ball(42, kWorldBody, Vec3::Zero())), "body_a: unknown body id 42");
  EXPECT_EQ(Rejected(world, Ball(a, 43, Vec3::Zero())), "body_b: unknown body id 43");
  EXPECT_NE(Rejected(world, Ball(a, a, Vec3::Zero())).find("cannot be jointed to itself (id 1)"), std::string::npos);
  EXPECT_EQ(Rejected(world, Ball(a, kWorldBody, Vec3(0, nan, 0))), "anchor must be finite, got (0, nan, 0)");
  EXPECT_NE(Rejected(world, Ball(wall, kWorldBody, Vec3::Zero())).find("at least one dynamic body"),
            std::string::npos);

  JointSettings distance = Ball(a, kWorldBody, Vec3(0, 0, 2));
  distance.kind = JointKind::kDistance;
  distance.length = 0.0;
  EXPECT_EQ(Rejected(world, distance), "length must be a finite number > 0, got 0");
  distance.length = -1.0;
  EXPECT_EQ(Rejected(world, distance), "length must be a finite number > 0, got -1");
  distance.length.reset();
  distance.anchor = Vec3(0, 0, 1);  // at the centre of mass: no default length
  EXPECT_NE(Rejected(world, distance).find("length must be given"), std::string::npos);

  JointSettings hinge = Ball(a, kWorldBody, Vec3(0, 0, 2));
  hinge.kind = JointKind::kHinge;
  EXPECT_EQ(Rejected(world, hinge), "axis is required for a hinge joint");
  hinge.axis = Vec3::Zero();
  EXPECT_EQ(Rejected(world, hinge), "axis must be a finite nonzero vector, got (0, 0, 0)");
  hinge.axis = Vec3::UnitY();
  hinge.limits = std::make_pair(0.5, -0.5);
  EXPECT_EQ(Rejected(world, hinge), "limits must have lower <= upper, got lower 0.5 > upper -0.5");
  hinge.limits = std::make_pair(-4.0, 0.5);
  EXPECT_EQ(Rejected(world, hinge), "limits.lower must be in [-3.141592654, 3.141592654], got -4");

  JointSettings ball = Ball(a, kWorldBody, Vec3(0, 0, 2));
  ball.axis = Vec3::UnitX();
  EXPECT_EQ(Rejected(world, ball), "axis applies to hinge joints only, not ball");
  ball.axis.reset();
  ball.length = 1.0;
  EXPECT_EQ(Rejected(world, ball), "length applies to distance joints only, not ball");
}

// Verifies that joint ids count up from 1 and are never reused, and that
// removing a body removes its joints and only those.
TEST(JointTest, IdsAreNeverReusedAndBodyRemovalTakesItsJoints) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 1));
  const BodyId b = AddSphere(world, Vec3(0, 0, 2));
  const BodyId c = AddSphere(world, Vec3(0, 0, 3));
  JointId ab = 0, bc = 0, top = 0, again = 0;
  ASSERT_TRUE(world.AddJoint(Ball(a, b, Vec3(0, 0, 1.5)), &ab).ok());
  ASSERT_TRUE(world.AddJoint(Ball(b, c, Vec3(0, 0, 2.5)), &bc).ok());
  ASSERT_TRUE(world.AddJoint(Ball(c, kWorldBody, Vec3(0, 0, 3.5)), &top).ok());
  EXPECT_EQ(ab, 1);
  EXPECT_EQ(bc, 2);
  EXPECT_EQ(top, 3);
  ASSERT_TRUE(world.RemoveJoint(bc).ok());
  EXPECT_EQ(world.RemoveJoint(bc).message(), "unknown joint id 2");
  ASSERT_TRUE(world.AddJoint(Ball(b, c, Vec3(0, 0, 2.5)), &again).ok());
  EXPECT_EQ(again, 4);
  ASSERT_TRUE(world.RemoveBody(b).ok());
  ASSERT_EQ(world.joints().size(), 1u);
  EXPECT_EQ(world.joints()[0].id, top);
  world.Clear();
  EXPECT_TRUE(world.joints().empty());
  EXPECT_EQ(world.next_joint_id, 1);
}

// Verifies that joints are part of the world hash, and that a world without
// joints hashes as before joints existed (no bytes added).
TEST(JointTest, JointsChangeTheWorldHash) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 1));
  const uint64_t before = HashWorldState(world);
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(Ball(a, kWorldBody, Vec3(0, 0, 2)), &id).ok());
  EXPECT_NE(HashWorldState(world), before);
  ASSERT_TRUE(world.RemoveJoint(id).ok());
  EXPECT_EQ(HashWorldState(world), before);
}

}  // namespace
}  // namespace contactsim
