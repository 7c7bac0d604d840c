// Tests of the barrier method's prediction (affine_prediction.h): the
// rotational rows of q_pred are service/physics's midpoint rotation, and
// EndAngularMomentum inverts it, so a free body's steps chain without loss.
#include "service/contact/barrier/affine_prediction.h"

#include <gtest/gtest.h>

#include <cmath>

#include "service/physics/body_settings.h"
#include "service/physics/integrator.h"

namespace contactsim {
namespace {

constexpr double kH = 1.0 / 240.0;  // s

RigidBody SpinningBox(const Vec3& w) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3(0.05, 0.1, 0.2);  // three distinct moments
  s.position = Vec3(1, 2, 3);
  s.linear_velocity = Vec3(0.5, -1, 2);
  s.angular_velocity = w;
  s.orientation = Eigen::Vector4d(0.9, 0.1, -0.3, 0.2);
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  return b;
}

// Verifies that the predicted A is the midpoint rotation of the body (so a
// rotation: A A^T = I to round-off) and p is implicit Euler's
// p + h v + h^2 F / m.
TEST(AffinePrediction, RotatesByTheMidpointRuleAndTranslatesByImplicitEuler) {
  RigidBody b = SpinningBox(Vec3(3, -2, 5));
  b.force = Vec3(0, 0, -9.81 * b.mass);
  Vec12 q, qdot;
  RigidToAffine(b, &q, &qdot);
  const Vec12 q_pred = PredictAffine(b, q, qdot, kH);
  const Mat3 A = AffineMatrix(q_pred);
  EXPECT_LT((A * A.transpose() - Mat3::Identity()).norm(), 1e-15);
  const Mat3 R = MidpointRotation(b.q, b.L, b.inv_inertia_body, kH).toRotationMatrix();
  EXPECT_LT((A - R).norm(), 1e-15);
  const Vec3 p = b.x + kH * b.LinearVelocity() + kH * kH * Vec3(0, 0, -9.81);
  EXPECT_LT((AffinePosition(q_pred) - p).norm(), 1e-15);
}

// Verifies that a torque adds h tau to L before the rotation (as the
// integrator's IntegrateMomenta then IntegratePositions).
TEST(AffinePrediction, TorqueTurnsTheMomentumFirst) {
  RigidBody b = SpinningBox(Vec3(1, 1, 1));
  b.torque = Vec3(0.2, -0.1, 0.3);
  Vec12 q, qdot;
  RigidToAffine(b, &q, &qdot);
  const Mat3 A = AffineMatrix(PredictAffine(b, q, qdot, kH));
  const Mat3 R = MidpointRotation(b.q, b.L + kH * b.torque, b.inv_inertia_body, kH).toRotationMatrix();
  EXPECT_LT((A - R).norm(), 1e-15);
}

// Verifies that EndAngularMomentum inverts the midpoint rotation: over 2400
// torque-free steps of an asymmetric box, each step's L taken back from its
// rotations, |L| and the kinetic energy stay to round-off (1e-11: measured
// 1.2e-12 after the 2400 steps).
TEST(AffinePrediction, EndMomentumChainsFreeStepsWithoutLoss) {
  RigidBody b = SpinningBox(Vec3(1, 1, 1));
  const double l0 = b.L.norm(), e0 = b.KineticEnergy();
  for (int step = 0; step < 2400; ++step) {
    const Quat q1 = MidpointRotation(b.q, b.L, b.inv_inertia_body, kH);
    b.L = EndAngularMomentum(b, b.q, q1, kH);
    b.q = q1;
  }
  EXPECT_NEAR(b.L.norm(), l0, 1e-11 * l0);
  EXPECT_NEAR(b.KineticEnergy(), e0, 1e-11 * e0);
}

// Verifies that a sphere's end momentum is I w for the w of its turn (no
// gyroscopic term for an isotropic body).
TEST(AffinePrediction, SphereEndsWithTheSpinOfItsTurn) {
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = 0.1;
  RigidBody b;
  ASSERT_TRUE(CreateBody(s, Material{}, &b).ok());
  const Vec3 w(0, 10, 0);  // rad/s
  const Quat q1 = b.q * QuatFromRotationVector(Vec3(0, 2 * std::atan(0.5 * kH * 10), 0));
  const Vec3 L = EndAngularMomentum(b, b.q, q1, kH);
  EXPECT_LT((L - b.inertia_body * w).norm(), 1e-12 * L.norm());
}

}  // namespace
}  // namespace contactsim
