// Tests of penalty's impact stage (service/contact/penalty/penalty_impacts.h)
// against Newton's impact law, and of which worlds it leaves to the springs.
#include "service/contact/penalty/penalty_impacts.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "service/contact/penalty/penalty_method.h"
#include "service/physics/body_settings.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::MethodSim;

BodyId AddBall(World& world, double x, double v, double mass, double e, double friction) {
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = 0.05;
  s.mass = mass;
  s.position = Vec3(x, 0, 0);
  s.linear_velocity = Vec3(v, 0, 0);
  s.restitution = e;
  s.friction = friction;
  return testing::AddValidBody(world, s);
}

// Verifies Newton's law for a head-on pair of unequal masses, without
// gravity: a ball of m_a at v0 into one of m_b at rest, 1 mm apart, leaves
// them at v_a = (m_a - e m_b) v0 / (m_a + m_b) and v_b = (1 + e) m_a v0 /
// (m_a + m_b) (Hahn 1988), to 1e-9 v0 at every mass ratio and e, and the
// step of the impact reports the contact with a push on B. The springs
// alone miss it by the dashpot's model (docs/methods/penalty.md, "Damping
// from restitution"); the stage gives it exactly.
TEST(PenaltyImpactsTest, HeadOnPairLeavesWithNewtonsLawAtEveryMassRatio) {
  constexpr double kV0 = 2.0;      // m/s
  constexpr double kTolerance = 1e-9;  // of v0: one impulse in double precision
  for (double ratio : {1.0, 3.0, 100.0, 0.01}) {
    for (double e : {0.0, 0.3, 0.7, 1.0}) {
      MethodSim sim("penalty");
      sim.world.gravity.setZero();
      const double ma = 1.0, mb = ma / ratio;
      const BodyId a = AddBall(sim.world, 0.0, kV0, ma, e, 0.0);
      const BodyId b = AddBall(sim.world, 0.101, 0.0, mb, e, 0.0);
      double pushed = 0.0;  // N, largest normal value reported
      for (int i = 0; i < 24; ++i) {
        sim.Step();
        for (const Contact& c : sim.contacts) pushed = std::max(pushed, c.normal_value);
      }
      const double va = sim.world.Find(a)->LinearVelocity().x(), vb = sim.world.Find(b)->LinearVelocity().x();
      const double expect_a = (ma - e * mb) * kV0 / (ma + mb), expect_b = (1 + e) * ma * kV0 / (ma + mb);
      std::printf("m_a / m_b %g e %g: v_a %+.12f (%+.12f), v_b %+.12f (%+.12f)\n", ratio, e, va, expect_a, vb,
                  expect_b);
      EXPECT_NEAR(va, expect_a, kTolerance * kV0) << "ratio " << ratio << " e " << e;
      EXPECT_NEAR(vb, expect_b, kTolerance * kV0) << "ratio " << ratio << " e " << e;
      EXPECT_GT(pushed, 0.0) << "the impact was not reported, ratio " << ratio << " e " << e;
    }
  }
}

// Verifies that a world whose contacts all have friction and restitution 0
// and lie in components the ground holds runs no stage: a box dropped onto
// the ground and a sphere rolling on it end bit for bit where they end with
// impacts = springs.
TEST(PenaltyImpactsTest, FrictionalWorldWithoutRestitutionIsLeftToTheSprings) {
  auto run = [](const std::string& impacts) {
    MethodSim sim("penalty", {{"impacts", impacts}});
    testing::AddGround(sim.world, 0.0, 0.5);
    const BodyId box = testing::AddBox(sim.world, Vec3(0.1, 0.1, 0.1), Vec3(0, 0, 0.3), 0.0, 0.5);
    const BodyId ball = testing::AddSphere(sim.world, 0.1, Vec3(1, 0, 0.1), 0.0, 0.5, Vec3(1, 0, 0));
    for (int i = 0; i < 120; ++i) sim.Step();
    const RigidBody& b = *sim.world.Find(box);
    const RigidBody& s = *sim.world.Find(ball);
    return std::vector<double>{b.x.x(), b.x.y(), b.x.z(), b.P.z(), b.q.w(), s.x.x(), s.x.z(), s.L.y()};
  };
  EXPECT_EQ(run("sequential"), run("springs"));
}

// Verifies a glancing strike with friction and e = 0 in free flight: a
// sphere at v0 along x into an equal one at rest whose centre is 45 degrees
// off its path. With mu = 0.5 the contact sticks (it needs mu >= 2/7), so
// one impact leaves the contact point at rest along n and t: the normal
// impulse m v0 / (2 sqrt 2) and the tangential one m v0 / (7 sqrt 2)
// (K_n = 2 / m, K_t = 2 / m + 2 r^2 / I = 7 / m for solid spheres); the
// stage's Coulomb impulse (sequential_impacts.h) gives the spin the springs'
// friction would take over the contact. Checked to 2e-3 v0 at 0.1-10 kg.
TEST(PenaltyImpactsTest, GlancingFrictionalStrikeInFreeFlightSticks) {
  constexpr double kV0 = 1.0, kR = 0.05;
  constexpr double kTolerance = 2e-3;  // of v0: the stage's cascade stops at 1e-3 of the strike
  for (double mass : {0.1, 1.0, 10.0}) {
    MethodSim sim("penalty");
    sim.world.gravity.setZero();
    const double off = 2 * kR / std::sqrt(2.0) + 1e-4 / std::sqrt(2.0);  // 0.1 mm apart along n
    const BodyId a = AddBall(sim.world, -off, kV0, mass, 0.0, 0.5);
    BodySettings s;
    s.shape = ShapeType::kSphere;
    s.radius = kR;
    s.mass = mass;
    s.position = Vec3(0, off, 0);
    s.restitution = 0.0;
    s.friction = 0.5;
    const BodyId b = testing::AddValidBody(sim.world, s);
    for (int i = 0; i < 24; ++i) sim.Step();
    const RigidBody& A = *sim.world.Find(a);
    const RigidBody& B = *sim.world.Find(b);
    const Vec3 n = Vec3(1, 1, 0).normalized(), t = Vec3(1, -1, 0).normalized();
    const double jn = mass * kV0 / (2 * std::sqrt(2.0)), jt = mass * kV0 / (7 * std::sqrt(2.0));
    const Vec3 vb = (jn * n + jt * t) / mass;
    const Vec3 va = Vec3(kV0, 0, 0) - vb;
    EXPECT_LT((B.LinearVelocity() - vb).norm(), kTolerance * kV0) << mass << " kg: " << B.LinearVelocity().transpose();
    EXPECT_LT((A.LinearVelocity() - va).norm(), kTolerance * kV0) << mass << " kg: " << A.LinearVelocity().transpose();
    // the spins turn the contact point with the bodies: equal, about z
    const double I = 0.4 * mass * kR * kR;
    EXPECT_NEAR(B.AngularVelocity().z(), kR * jt / I, kTolerance * kV0 / kR) << mass << " kg";
    EXPECT_NEAR(A.AngularVelocity().z(), kR * jt / I, kTolerance * kV0 / kR) << mass << " kg";
  }
}

}  // namespace
}  // namespace contactsim
