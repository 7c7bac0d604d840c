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
  EXPECT_EQ(Rejected(world, ball), "axis applies to hinge and prismatic joints only, not ball");
  ball.axis.reset();
  ball.length = 1.0;
  EXPECT_EQ(Rejected(world, ball), "length applies to distance joints only, not ball");
}

// Verifies that a prismatic joint and the joint dynamics reject garbage
// with a message naming the field and the value, and add nothing: a zero or
// NaN axis, NaN or inverted limits, negative or NaN damping and friction,
// damping or friction on a kind without a joint coordinate.
TEST(JointTest, RejectsBadSliderAndDynamicsSettings) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 1));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  JointSettings slider = Ball(a, kWorldBody, Vec3(0, 0, 1));
  slider.kind = JointKind::kPrismatic;
  EXPECT_EQ(Rejected(world, slider), "axis is required for a prismatic joint");
  slider.axis = Vec3::Zero();
  EXPECT_EQ(Rejected(world, slider), "axis must be a finite nonzero vector, got (0, 0, 0)");
  slider.axis = Vec3(nan, 0, 1);
  EXPECT_EQ(Rejected(world, slider), "axis must be a finite nonzero vector, got (nan, 0, 1)");
  slider.axis = Vec3::UnitX();
  slider.limits = std::make_pair(0.5, -0.5);
  EXPECT_EQ(Rejected(world, slider), "limits must have lower <= upper, got lower 0.5 > upper -0.5");
  slider.limits = std::make_pair(nan, 0.5);
  EXPECT_EQ(Rejected(world, slider), "limits.lower must be a finite number, got nan");
  slider.limits = std::make_pair(-1.0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(Rejected(world, slider), "limits.upper must be a finite number, got inf");
  slider.limits = std::make_pair(-10.0, 10.0);  // metres: beyond a hinge's [-pi, pi], fine for a slider
  slider.damping = -1.0;
  EXPECT_EQ(Rejected(world, slider), "damping must be a finite number >= 0, got -1");
  slider.damping = nan;
  EXPECT_EQ(Rejected(world, slider), "damping must be a finite number >= 0, got nan");
  slider.damping = 0.5;
  slider.friction = -0.1;
  EXPECT_EQ(Rejected(world, slider), "friction must be a finite number >= 0, got -0.1");
  JointSettings ball = Ball(a, kWorldBody, Vec3(0, 0, 2));
  ball.friction = 0.3;
  EXPECT_EQ(Rejected(world, ball), "friction applies to hinge and prismatic joints only, not ball (got 0.3)");
  ball.friction = 0.0;
  ball.damping = 2.0;
  EXPECT_EQ(Rejected(world, ball), "damping applies to hinge and prismatic joints only, not ball (got 2)");
  ball.damping = 0.0;
  ball.limits = std::make_pair(-0.1, 0.1);
  EXPECT_EQ(Rejected(world, ball), "limits apply to hinge and prismatic joints only, not ball");

  slider.friction = 0.25;
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(slider, &id).ok());
  const Joint* j = world.FindJoint(id);
  EXPECT_EQ(j->kind, JointKind::kPrismatic);
  EXPECT_TRUE(j->limited);
  EXPECT_EQ(j->lower, -10.0);
  EXPECT_EQ(j->damping, 0.5);
  EXPECT_EQ(j->friction, 0.25);
  JointKind parsed = JointKind::kBall;
  ASSERT_TRUE(ParseJointKind("prismatic", &parsed));
  EXPECT_EQ(parsed, JointKind::kPrismatic);
  EXPECT_STREQ(JointKindName(JointKind::kPrismatic), "prismatic");
}

// Verifies JointPosition and JointVelocity against the motion they measure:
// a slider's slide and rate along an axis turning with A (the rate is the
// derivative of the slide, checked by a finite difference of the poses), and
// a hinge's angle and rate; 0 for kinds without a coordinate.
TEST(JointTest, JointPositionAndVelocityMeasureTheCoordinate) {
  World world;
  const BodyId a = AddSphere(world, Vec3(0, 0, 1));
  const BodyId b = AddSphere(world, Vec3(0.5, 0, 1));
  JointSettings s = Ball(b, a, Vec3(0.2, 0.1, 1.0));
  s.kind = JointKind::kPrismatic;
  s.axis = Vec3(1, 1, 0);
  JointId id = 0;
  ASSERT_TRUE(world.AddJoint(s, &id).ok());
  const Joint j = *world.FindJoint(id);
  RigidBody* body_a = world.Find(b);  // the joint's A (body_a = b)
  RigidBody* body_b = world.Find(a);
  EXPECT_NEAR(JointPosition(j, *body_a, body_b), 0.0, 1e-15);
  // B moved 0.3 m along the axis and 0.1 m across it: the slide is 0.3
  body_b->x += 0.3 * Vec3(1, 1, 0).normalized() + 0.1 * Vec3(0, 0, 1);
  EXPECT_NEAR(JointPosition(j, *body_a, body_b), 0.3, 1e-12);
  // both moving and turning: the rate is d(slide)/dt
  body_a->SetVelocity(Vec3(0.1, -0.2, 0.3), Vec3(0.4, -0.5, 0.6));
  body_b->SetVelocity(Vec3(-0.3, 0.2, 0.1), Vec3(0.2, 0.1, -0.3));
  const double rate = JointVelocity(j, *body_a, body_b);
  const double dt = 1e-6;
  auto advance = [dt](RigidBody& r, double sign) {
    const Vec3 w = r.AngularVelocity();
    r.x += sign * dt * r.LinearVelocity();
    r.q = (Quat(Eigen::AngleAxisd(sign * dt * w.norm(), w.normalized())) * r.q).normalized();
  };
  RigidBody plus_a = *body_a, plus_b = *body_b, minus_a = *body_a, minus_b = *body_b;
  advance(plus_a, 1.0), advance(plus_b, 1.0), advance(minus_a, -1.0), advance(minus_b, -1.0);
  const double fd = (JointPosition(j, plus_a, &plus_b) - JointPosition(j, minus_a, &minus_b)) / (2.0 * dt);
  EXPECT_NEAR(rate, fd, 1e-8);

  JointSettings h = Ball(a, kWorldBody, Vec3(0, 0, 1));
  h.kind = JointKind::kHinge;
  h.axis = Vec3::UnitZ();
  ASSERT_TRUE(world.AddJoint(h, &id).ok());
  const Joint hinge = *world.FindJoint(id);
  body_b->q = Quat(Eigen::AngleAxisd(0.7, Vec3::UnitZ())) * body_b->q;
  body_b->SetVelocity(Vec3::Zero(), Vec3(0.1, 0.2, 1.5));
  EXPECT_NEAR(JointPosition(hinge, *body_b, nullptr), -0.7, 1e-12);  // B is the world: A turned +0.7
  EXPECT_NEAR(JointVelocity(hinge, *body_b, nullptr), -1.5, 1e-12);
  const Joint ball = *world.FindJoint(1);
  Joint as_ball = ball;
  as_ball.kind = JointKind::kBall;
  EXPECT_EQ(JointPosition(as_ball, *body_a, body_b), 0.0);
  EXPECT_EQ(JointVelocity(as_ball, *body_a, body_b), 0.0);
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
