// Scenes from the contact-methods issue, run through the registry by name:
// a box landing flat on its four corners (every registered method, lcp with
// each solver) and the impulse method's tunnelling case. The incline, the
// zero-restitution drop and the stacks these tests once ran on hand lists
// of methods are the mechanics suite's now (tests/contact/mechanics_*_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "service/physics/body_settings.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;
using testing::AddValidBody;
using testing::MethodConfig;

using Sim = testing::MethodSim;

class BoxLandingTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies that the four corners of a box landing flat collide together: it
// rebounds to e^2 h (the table's bounce bound on apex / h) and does not
// start to spin (one corner after another would give the first the whole
// impulse and tip the box; impulse's velocity tolerance leaves ~2e-6 rad/s).
TEST_P(BoxLandingTest, BoxLandingFlatReboundsStraight) {
  const MethodConfig& config = GetParam();
  const double e = 0.5, h = 1.0, half = 0.1;
  Sim sim(config.method, config.params);
  AddGround(sim.world, e, 0.5);
  const BodyId id = AddBox(sim.world, half, Vec3(0, 0, h + half), e, 0.5);
  if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).restitution, "restitution")) return;
  bool bounced = false;
  double apex = 0.0, last_vz = 0.0, worst_spin = 0.0;
  for (int i = 0; i < 480; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(id);
    const double vz = b.LinearVelocity().z();
    worst_spin = std::max(worst_spin, b.AngularVelocity().norm());
    if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.x.z() - half);
      if (vz < 0.0) break;
    }
    last_vz = vz;
  }
  std::printf("%-10s box landing flat rebounds to %.5f m (e^2 h = %.5f m), spin %.2g rad/s\n", config.label.c_str(),
              apex, e * e * h, worst_spin);
  testing::MechanicsChecks checks(config.label);
  checks.Expect("landing flat apex", apex / h, e * e, testing::TolerancesOf(config.label).bounce);
  checks.Expect("landing flat spin", worst_spin, 0.0, 1e-4);
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, BoxLandingTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

// Verifies that a sphere at 50 m/s does not pass through a 2 cm thick static
// box (collision time by backtracking): it ends on the near side.
TEST(ImpulseScenarios, FastSphereDoesNotTunnelThroughThinBox) {
  Sim sim("impulse");
  sim.world.gravity.setZero();
  BodySettings wall;
  wall.shape = ShapeType::kBox;
  wall.half_extents = Vec3(0.01, 1.0, 1.0);  // 2 cm thick in x
  wall.fixed = true;
  wall.restitution = 0.0;
  AddValidBody(sim.world, wall);
  const double r = 0.05;
  const BodyId ball = AddSphere(sim.world, r, Vec3(-1.0, 0, 0), 0.0, 0.5, Vec3(50.0, 0, 0));
  for (int i = 0; i < 60; ++i) sim.Step();  // 50 m/s covers 0.21 m per step
  const RigidBody& b = *sim.world.Find(ball);
  EXPECT_LT(b.x.x(), -0.01 - r + 2e-3);  // on the near face, within the slop
  EXPECT_LT(b.LinearVelocity().x(), 1e-6);  // stopped (e = 0), not moving through
}

}  // namespace
}  // namespace contactsim
