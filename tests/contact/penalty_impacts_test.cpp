// Tests of penalty's impact stage (service/contact/penalty/penalty_impacts.h)
// against Newton's impact law, and of which worlds it leaves to the springs.
#include "service/contact/penalty/penalty_impacts.h"

#include <gtest/gtest.h>

#include <algorithm>
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
// runs no stage: a box dropped onto the ground and a sphere rolling on it
// end bit for bit where they end with impacts = springs.
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

}  // namespace
}  // namespace contactsim
