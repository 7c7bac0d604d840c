// Tests of the impulse method against analytic results.
#include "service/contact/impulse/impulse_method.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "service/physics/body_settings.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;

struct Sim {
  World world;
  CollisionDetector detector;
  ImpulseMethod method;
  ContactSet contacts;
  StepStats Step() { return method.Step(world, detector, &contacts); }
};

// Highest z of a body's centre after its first contact with the ground,
// sampled every step (the first rebound apex).
double FirstReboundApex(Sim& sim, BodyId id, int max_steps) {
  bool bounced = false;
  double apex = -1e9;
  double last_vz = 0.0;
  for (int i = 0; i < max_steps; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(id);
    const double vz = b.LinearVelocity().z();
    if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.x.z());
      if (vz < 0.0) break;
    }
    last_vz = vz;
  }
  return apex;
}

class BounceTest : public ::testing::TestWithParam<double> {};

// Verifies that a sphere dropped from h rebounds to e^2 h within 2%
// (Newton's law of restitution, v+ = -e v-).
TEST_P(BounceTest, SphereReboundsToESquaredTimesDropHeight) {
  const double e = GetParam();
  const double r = 0.1, h = 1.0;  // h: drop height of the lowest point
  Sim sim;
  AddGround(sim.world, e, 0.5);
  const BodyId ball = AddSphere(sim.world, r, Vec3(0, 0, h + r), e);
  const double apex = FirstReboundApex(sim, ball, 2000) - r;
  if (e == 0.0) {
    // no bounce: it comes to rest on the plane within the slop
    EXPECT_NEAR(sim.world.Find(ball)->x.z() - r, 0.0, 2e-3);
  } else {
    EXPECT_NEAR(apex, e * e * h, 0.02 * e * e * h) << "e = " << e;
    RecordProperty("apex_m", std::to_string(apex));
    std::printf("e = %.2f: rebound apex %.5f m, analytic %.5f m (%.2f%%)\n", e, apex, e * e * h,
                100.0 * (apex - e * e * h) / (e * e * h));
  }
}

INSTANTIATE_TEST_SUITE_P(Restitution, BounceTest, ::testing::Values(0.0, 0.5, 0.9));

// Verifies that a box sliding at v0 with friction mu stops after v0^2 / (2 mu g)
// within 3% (Coulomb friction, constant deceleration mu g).
TEST(ImpulseMethod, SlidingBoxStopsAtAnalyticDistance) {
  const double mu = 0.4, v0 = 3.0;
  Sim sim;
  AddGround(sim.world, 0.0, mu);
  const double half = 0.1;
  const BodyId box = AddBox(sim.world, Vec3::Constant(half), Vec3(0, 0, half), 0.0, mu, Vec3(v0, 0, 0));
  for (int i = 0; i < 2400; ++i) sim.Step();
  const double expected = v0 * v0 / (2.0 * mu * kG);
  const RigidBody& b = *sim.world.Find(box);
  EXPECT_NEAR(b.x.x(), expected, 0.03 * expected);
  EXPECT_NEAR(b.LinearVelocity().norm(), 0.0, 1e-3);
}

// Verifies that a box resting on the plane stays put: no creep, no bounce.
TEST(ImpulseMethod, RestingBoxStaysAtRest) {
  Sim sim;
  AddGround(sim.world, 0.5, 0.5);
  const double half = 0.25;
  const BodyId box = AddBox(sim.world, Vec3::Constant(half), Vec3(0, 0, half), 0.5, 0.5);
  for (int i = 0; i < 2400; ++i) sim.Step();  // 10 s
  const RigidBody& b = *sim.world.Find(box);
  EXPECT_NEAR(b.x.z(), half, 2e-3);  // within the slop
  // sequential impulses stop at a velocity tolerance, which leaves a creep
  // of a few micrometres over 10 s (measured 3.4e-6 m); bound it at 10 um
  EXPECT_NEAR(b.x.x(), 0.0, 1e-5);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-3);
  EXPECT_LT(b.AngularVelocity().norm(), 1e-3);
}

// Verifies that a head-on collision of two spheres in free space conserves
// linear momentum exactly and ends with the relative speed scaled by e.
TEST(ImpulseMethod, SphereCollisionConservesMomentum) {
  const double e = 0.7;
  Sim sim;
  sim.world.gravity.setZero();
  const BodyId a = AddSphere(sim.world, 0.1, Vec3(-0.5, 0, 0), e, 0.0, Vec3(2, 0, 0));
  const BodyId b = AddSphere(sim.world, 0.2, Vec3(0.5, 0.05, 0), e, 0.0, Vec3(-1, 0, 0));
  auto momentum = [&] { return Vec3(sim.world.Find(a)->P + sim.world.Find(b)->P); };
  auto angular = [&] {
    Vec3 L = Vec3::Zero();
    for (BodyId id : {a, b}) {
      const RigidBody& r = *sim.world.Find(id);
      L += r.L + r.x.cross(r.P);
    }
    return L;
  };
  const Vec3 p0 = momentum();
  const Vec3 l0 = angular();
  for (int i = 0; i < 240; ++i) sim.Step();
  // tolerance: round-off of a few hundred additions of O(10) kg m/s values
  EXPECT_LT((momentum() - p0).norm(), 1e-10);
  EXPECT_LT((angular() - l0).norm(), 1e-9);
}

// Verifies Newton's cradle: five touching spheres with e = 1; the first hits
// at v and the last leaves with v within 2% while the others stay nearly at rest.
TEST(ImpulseMethod, NewtonsCradleTransfersMomentumToTheLastSphere) {
  const double r = 0.1, v = 1.0;
  Sim sim;
  sim.world.gravity.setZero();
  std::vector<BodyId> balls;
  balls.push_back(AddSphere(sim.world, r, Vec3(-0.3, 0, 0), 1.0, 0.0, Vec3(v, 0, 0)));
  for (int i = 0; i < 4; ++i) balls.push_back(AddSphere(sim.world, r, Vec3(2.0 * r * i, 0, 0), 1.0, 0.0));
  for (int i = 0; i < 120; ++i) sim.Step();
  EXPECT_NEAR(sim.world.Find(balls.back())->LinearVelocity().x(), v, 0.02 * v);
  for (size_t i = 0; i + 1 < balls.size(); ++i) {
    EXPECT_LT(std::abs(sim.world.Find(balls[i])->LinearVelocity().x()), 0.02 * v) << "ball " << i;
  }
}

// Verifies that parameters are validated as a whole: a bad value names the
// parameter, and nothing changes.
TEST(ImpulseMethod, RejectsBadParametersAndKeepsTheOldOnes) {
  ImpulseMethod m;
  Status st = m.SetParams({{"iterations", "50"}, {"slop", "-1"}});
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("slop"), std::string::npos) << st.message();
  EXPECT_EQ(m.params().iterations, 30);
  st = m.SetParams({{"nosuch", "1"}});
  EXPECT_NE(st.message().find("unknown parameter \"nosuch\""), std::string::npos) << st.message();
  st = m.SetParams({{"toi", "newton"}});
  EXPECT_NE(st.message().find("toi"), std::string::npos) << st.message();
  EXPECT_TRUE(m.SetParams({{"iterations", "50"}, {"toi", "bisection"}}).ok());
  EXPECT_EQ(m.params().iterations, 50);
}

}  // namespace
}  // namespace contactsim
