// Hand-computed cases of the sphere pair functions, through the public
// Collide() so that the dispatch and the conventions are checked too.
#include <gtest/gtest.h>

#include <cmath>

#include "service/collision/narrowphase.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing_util::Box;
using testing_util::Capsule;
using testing_util::Convex;
using testing_util::Ground;
using testing_util::Hull;
using testing_util::MakeBody;
using testing_util::Sphere;

// The inputs are short decimal numbers, so closed forms agree with the hand
// values to round-off of a few ulps of 1 m.
using testing_util::kTol;

void ExpectContact(const Contact& c, const Vec3& point, const Vec3& normal, double depth) {
  EXPECT_NEAR((c.point - point).norm(), 0.0, kTol) << c.point.transpose();
  EXPECT_NEAR((c.normal - normal).norm(), 0.0, kTol) << c.normal.transpose();
  EXPECT_NEAR(c.depth, depth, kTol);
}

// Verifies sphere-sphere: depth ra + rb - d, normal along the centres, point midway.
TEST(CollideSphereTest, SphereSphereOverlapMatchesHandValues) {
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.5, Vec3::Zero()), 3, Sphere(2, 0.3, Vec3(0.7, 0, 0)), 5, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0.45, 0, 0), Vec3(1, 0, 0), 0.1);
  EXPECT_EQ(out[0].a, 3);
  EXPECT_EQ(out[0].b, 5);
  EXPECT_EQ(out[0].id_a, 1);
  EXPECT_EQ(out[0].id_b, 2);
}

// Verifies that a gap below the margin is reported with depth = -gap, and a larger gap is not.
TEST(CollideSphereTest, SphereSphereGapIsSpeculativeWithinMargin) {
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.5, Vec3::Zero()), 0, Sphere(2, 0.3, Vec3(0.9, 0, 0)), 1, 0.2, &out), 1);
  ExpectContact(out[0], Vec3(0.55, 0, 0), Vec3(1, 0, 0), -0.1);
  out.clear();
  EXPECT_EQ(Collide(Sphere(1, 0.5, Vec3::Zero()), 0, Sphere(2, 0.3, Vec3(0.9, 0, 0)), 1, 0.05, &out), 0);
}

// Verifies sphere-plane on the ground: depth r - z, normal from the sphere into the plane.
TEST(CollideSphereTest, SphereOnGroundMatchesHandValues) {
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.5, Vec3(1, 2, 0.4)), 0, Ground(2), 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(1, 2, -0.05), Vec3(0, 0, -1), 0.1);
}

// Verifies that a plane body's pose is honoured: body normal +z rotated 90
// degrees about x is -y, so the solid side is y >= -0.2 for offset 0.2.
TEST(CollideSphereTest, SpherePlaneHonoursThePlanePose) {
  const RigidBody plane = MakeBody(2, Shape::Plane(Vec3::UnitZ(), 0.2), Vec3(0, 0, 1),
                                   Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())));
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.5, Vec3(0, -0.5, 0)), 0, plane, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0, -0.1, 0), Vec3(0, 1, 0), 0.2);
}

// Verifies sphere-box against a face, an edge and with the centre inside.
TEST(CollideSphereTest, SphereBoxFaceEdgeAndInsideMatchHandValues) {
  const RigidBody box = Box(2, Vec3(1, 0.5, 0.25), Vec3::Zero());
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(0, 0, 0.4)), 0, box, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0, 0, 0.225), Vec3(0, 0, -1), 0.05);

  out.clear();
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(1.1, 0, 0.35)), 0, box, 1, 0.0, &out), 1);
  const double d = std::sqrt(0.02);
  const Vec3 m = Vec3(1, 0, 1).normalized();
  ExpectContact(out[0], Vec3(1.1, 0, 0.35) - 0.5 * (0.2 + d) * m, -m, 0.2 - d);

  out.clear();
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(0.9, 0, 0)), 0, box, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0.85, 0, 0), Vec3(-1, 0, 0), 0.3);
}

// Verifies sphere-box with the box rotated 90 degrees about z (its long axis along y).
TEST(CollideSphereTest, SphereBoxHonoursTheBoxRotation) {
  const RigidBody box =
      Box(2, Vec3(1, 0.5, 0.25), Vec3::Zero(), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())));
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(0.6, 0, 0)), 0, box, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0.45, 0, 0), Vec3(-1, 0, 0), 0.1);
}

// Verifies sphere-capsule against the side and the cap, and for a rotated capsule.
TEST(CollideSphereTest, SphereCapsuleSideAndCapMatchHandValues) {
  ContactSet out;
  const RigidBody upright = Capsule(2, 0.1, 0.5, Vec3::Zero());
  ASSERT_EQ(Collide(Sphere(1, 0.3, Vec3(0.35, 0, 0.2)), 0, upright, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0.075, 0, 0.2), Vec3(-1, 0, 0), 0.05);

  out.clear();
  ASSERT_EQ(Collide(Sphere(1, 0.3, Vec3(0, 0, 0.85)), 0, upright, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0, 0, 0.575), Vec3(0, 0, -1), 0.05);

  out.clear();
  const RigidBody lying =
      Capsule(2, 0.1, 0.5, Vec3::Zero(), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY())));
  ASSERT_EQ(Collide(Sphere(1, 0.3, Vec3(0.45, 0, 0.35)), 0, lying, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0.45, 0, 0.075), Vec3(0, 0, -1), 0.05);
}

// Verifies sphere-convex on a cube hull: the same values as the closed-form box.
TEST(CollideSphereTest, SphereConvexMatchesTheBoxValues) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5);
  const RigidBody cube = Convex(2, Hull(corners), Vec3::Zero());
  ContactSet out;
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(0, 0, 0.6)), 0, cube, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0, 0, 0.45), Vec3(0, 0, -1), 0.1);

  out.clear();
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(0.6, 0, 0.6)), 0, cube, 1, 0.0, &out), 1);
  const double d = std::sqrt(0.02);
  EXPECT_NEAR(out[0].depth, 0.2 - d, kTol);
  EXPECT_NEAR((out[0].normal + Vec3(1, 0, 1).normalized()).norm(), 0.0, kTol);

  out.clear();
  ASSERT_EQ(Collide(Sphere(1, 0.2, Vec3(0.4, 0, 0)), 0, cube, 1, 0.0, &out), 1);
  ExpectContact(out[0], Vec3(0.35, 0, 0), Vec3(-1, 0, 0), 0.3);
}

}  // namespace
}  // namespace contactsim
