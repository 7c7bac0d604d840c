// Tests of the lcp method's impact handling (PredictImpact,
// lcp_contact_rows.h): a dropped ball rebounds to e^2 h0 whatever the phase
// of the impact within the step, with both solvers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <tuple>

#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::AddGround;
using testing::AddSphere;

constexpr double kRadius = 0.1;  // m

// The first apex of the ball's lowest point after its first bounce (m),
// dropped from rest with its lowest point h0 above a plane, both of
// restitution e, at the default dt = 1/240 s; -1 if it never rises.
double FirstApex(const std::string& solver, double e, double h0) {
  testing::MethodSim sim("lcp", {{"solver", solver}});
  AddGround(sim.world, e, 0.5);
  const BodyId ball = AddSphere(sim.world, kRadius, Vec3(0, 0, h0 + kRadius), e);
  bool bounced = false;
  double apex = -1.0, last_vz = 0.0;
  for (int i = 0; i < 3000; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(ball);
    const double vz = b.LinearVelocity().z();
    if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.x.z() - kRadius);
      if (vz < 0.0) break;
    }
    last_vz = vz;
  }
  return apex;
}

class LcpBounceTest : public ::testing::TestWithParam<std::tuple<const char*, double, double>> {};

// Verifies the rebound apex is e^2 h0 (Newton's law at the moment of
// impact, free flight before and after) within 2%. The drop heights put the
// impact at different phases of its step (at dt = 1/240 s the fall from h0
// lasts sqrt(2 h0 / g) / dt = 59.35, 78.89 and 121.64 steps), where
// Newton's law at the step's start was off by up to 4.3% (e = 0.5, 0.53 m).
// Sampling the apex once per step loses at most g dt^2 / 8 (2e-5 m).
TEST_P(LcpBounceTest, ReboundsToESquaredTimesDropHeight) {
  const auto [solver, e, h0] = GetParam();
  const double apex = FirstApex(solver, e, h0);
  EXPECT_NEAR(apex, e * e * h0, 0.02 * e * e * h0);
  std::printf("%s e=%.1f h0=%.2f: apex %.5f m, analytic %.5f m (%+.3f%%)\n", solver, e, h0, apex, e * e * h0,
              100.0 * (apex / (e * e * h0) - 1.0));
}

INSTANTIATE_TEST_SUITE_P(Drops, LcpBounceTest,
                         ::testing::Combine(::testing::Values("pgs", "lemke"), ::testing::Values(0.5, 0.9),
                                            ::testing::Values(0.3, 0.53, 1.26)));

// Verifies a ball with e = 0 does not rebound: the impact rule keeps the
// step-start rule (v+ = 0) when the rebound would land within the step.
TEST(LcpBounce, PlasticImpactDoesNotRebound) {
  testing::MethodSim sim("lcp");
  AddGround(sim.world, 0.0, 0.5);
  const BodyId ball = AddSphere(sim.world, kRadius, Vec3(0, 0, 0.9 + kRadius), 0.0);
  int touched_at = -1;
  double highest_after = -1.0;
  for (int i = 0; i < 400; ++i) {
    sim.Step();
    const double z = sim.world.Find(ball)->x.z() - kRadius;
    if (touched_at < 0 && !sim.contacts.empty()) touched_at = i;
    if (touched_at >= 0 && i > touched_at + 1) highest_after = std::max(highest_after, z);
  }
  ASSERT_GE(touched_at, 0) << "the ball never reached the plane";
  EXPECT_LT(highest_after, 1e-3);  // the slop: it may not leave the plane
}

}  // namespace
}  // namespace contactsim
