// Tests of the forward kinematics of a description against poses worked
// out by hand for each joint type, chained.
#include "service/model/model_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace contactsim::model {
namespace {

// Compositions of a few rotations: a few ulps.
constexpr double kTol = 1e-12;

Quat AxisAngle(const Vec3& axis, double angle) { return Quat(Eigen::AngleAxisd(angle, axis.normalized())); }

ModelJoint MakeJoint(const std::string& name, JointType type, const std::string& parent, const std::string& child,
                     const Vec3& p, const Quat& q, const Vec3& axis) {
  ModelJoint j;
  j.name = name;
  j.type = type;
  j.parent = parent;
  j.child = child;
  j.origin = Pose{p, q};
  j.axis = axis;
  return j;
}

// a -rev(z)-> b -pri(x)-> c -fix-> d, and a -float-> e, a -planar(z)-> f
ModelDescription Chain() {
  ModelDescription m;
  m.name = "chain";
  for (const char* n : {"a", "b", "c", "d", "e", "f"}) m.links.push_back(Link{n, std::nullopt, {}, {}});
  m.joints.push_back(MakeJoint("rev", JointType::kRevolute, "a", "b", Vec3(1, 0, 0), AxisAngle(Vec3::UnitZ(), kPi / 2),
                               Vec3::UnitZ()));
  m.joints.push_back(MakeJoint("pri", JointType::kPrismatic, "b", "c", Vec3(0, 1, 0), Quat::Identity(), Vec3::UnitX()));
  m.joints.push_back(MakeJoint("fix", JointType::kFixed, "c", "d", Vec3(0, 0, 2), AxisAngle(Vec3::UnitX(), kPi), Vec3::UnitX()));
  m.joints.push_back(MakeJoint("float", JointType::kFloating, "a", "e", Vec3(0, 0, 1), Quat::Identity(), Vec3::UnitX()));
  m.joints.push_back(MakeJoint("plane", JointType::kPlanar, "a", "f", Vec3::Zero(), Quat::Identity(), Vec3::UnitZ()));
  m.root_link = "a";
  return m;
}

void ExpectPose(const Pose& p, const Vec3& position, const Quat& orientation, const std::string& what) {
  EXPECT_LT((p.position - position).norm(), kTol) << what << ": " << p.position.transpose();
  EXPECT_LT(p.orientation.angularDistance(orientation), kTol) << what;
}

// Verifies each joint type's motion and their chaining: b turns about its
// own z at (1, 0, 0); c slides along b's x from b's (0, 1, 0); d sits 2
// above c, flipped; e is free; f moves in a's xy plane and turns about z.
TEST(ModelKinematicsTest, EveryJointTypeMovesItsChild) {
  const ModelDescription m = Chain();
  EXPECT_EQ(ModelCoordinateCount(m), 1 + 1 + 0 + 7 + 3);
  const double rev = 0.3, pri = 0.25;
  const Quat e_rot = AxisAngle(Vec3(1, 2, 3), 0.7);
  const std::vector<double> q = {rev, pri, 0.5, -0.5, 0.25, e_rot.w(), e_rot.x(), e_rot.y(), e_rot.z(), 0.4, -0.2, 1.1};
  const Pose root{Vec3(0, 0, 5), AxisAngle(Vec3::UnitY(), 0.2)};
  std::vector<Pose> poses;
  const Status st = LinkWorldPoses(m, root, q, &poses);
  ASSERT_TRUE(st.ok()) << st.message();
  auto world = [&](const Vec3& p) -> Vec3 { return root.position + root.orientation * p; };
  ExpectPose(poses[0], root.position, root.orientation, "a");
  const Quat b_rot = AxisAngle(Vec3::UnitZ(), kPi / 2 + rev);
  ExpectPose(poses[1], world(Vec3(1, 0, 0)), root.orientation * b_rot, "b");
  const Vec3 c_in_a = Vec3(1, 0, 0) + b_rot * Vec3(pri, 1, 0);
  ExpectPose(poses[2], world(c_in_a), root.orientation * b_rot, "c");
  const Quat d_rot = b_rot * AxisAngle(Vec3::UnitX(), kPi);
  ExpectPose(poses[3], world(c_in_a + b_rot * Vec3(0, 0, 2)), root.orientation * d_rot, "d");
  ExpectPose(poses[4], world(Vec3(0.5, -0.5, 1.25)), root.orientation * e_rot, "e");
  Vec3 t1, t2;
  PerpendicularBasis(Vec3::UnitZ(), &t1, &t2);
  ExpectPose(poses[5], world(0.4 * t1 - 0.2 * t2), root.orientation * AxisAngle(Vec3::UnitZ(), 1.1), "f");
}

// Verifies that a continuous joint's pose repeats every full turn.
TEST(ModelKinematicsTest, FullTurnGivesTheSamePose) {
  ModelDescription m = Chain();
  m.joints[0].type = JointType::kContinuous;
  std::vector<double> q(ModelCoordinateCount(m), 0.0);
  q[5] = 1.0;  // e's quaternion w
  std::vector<Pose> p0, p1;
  q[0] = 0.4;
  ASSERT_TRUE(LinkWorldPoses(m, Pose{}, q, &p0).ok());
  q[0] = 0.4 + 2 * kPi;
  ASSERT_TRUE(LinkWorldPoses(m, Pose{}, q, &p1).ok());
  for (size_t i = 0; i < p0.size(); ++i) ExpectPose(p1[i], p0[i].position, p0[i].orientation, m.links[i].name);
}

// Verifies that a wrong number of coordinates and a NaN are refused.
TEST(ModelKinematicsTest, BadCoordinatesAreRefused) {
  const ModelDescription m = Chain();
  std::vector<Pose> poses;
  Status st = LinkWorldPoses(m, Pose{}, {0.1}, &poses);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("takes 12 joint coordinates, got 1"), std::string::npos) << st.message();
  std::vector<double> q(12, 0.0);
  q[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(LinkWorldPoses(m, Pose{}, q, &poses).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace contactsim::model
