// Pendulums through the contact methods that honour joints (impulse,
// penalty, lcp with both solvers, xpbd), against analytic periods, the
// constraint itself and energy (xpbd's energy: xpbd_joint_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/contact/joint_test_util.h"

namespace contactsim {
namespace {

using testing::AddJoint;
using testing::AddSphere;
using testing::JointSim;
using testing::kG;

const Vec3 kPivot(0, 0, 2);  // m, world

// Period (s) from the times at which x crosses zero upwards or downwards,
// linearly interpolated between steps: twice the mean spacing of the
// crossings between the first and the last.
double MeasurePeriod(JointSim& sim, BodyId bob, double duration) {
  std::vector<double> crossings;
  double last_x = sim.world.Find(bob)->x.x();
  double last_t = sim.world.time;
  while (sim.world.time < duration) {
    sim.Step();
    const double x = sim.world.Find(bob)->x.x();
    if ((last_x < 0.0) != (x < 0.0)) crossings.push_back(last_t + (sim.world.time - last_t) * last_x / (last_x - x));
    last_x = x;
    last_t = sim.world.time;
  }
  if (crossings.size() < 2) return 0.0;
  return 2.0 * (crossings.back() - crossings.front()) / (crossings.size() - 1);
}

class JointPendulumTest : public ::testing::TestWithParam<const char*> {};

// Verifies that a small-angle point pendulum (a sphere on a distance joint
// to the world, through its centre, so it does not rotate) swings with the
// period 2 pi sqrt(l / g) to 0.5% over 10 s. At 0.05 rad the finite-amplitude
// correction is 1 + theta^2 / 16 = 1.00016, well inside.
TEST_P(JointPendulumTest, SmallAnglePeriodIsTwoPiRootLOverG) {
  const double l = 1.0, theta0 = 0.05;
  JointSim sim(GetParam());
  const BodyId bob = AddSphere(sim.world, 0.05, kPivot + l * Vec3(std::sin(theta0), 0, -std::cos(theta0)), 0.0);
  AddJoint(sim.world, JointKind::kDistance, bob, kWorldBody, kPivot);
  const double period = MeasurePeriod(sim, bob, 10.0);
  const double expected = 2.0 * kPi * std::sqrt(l / kG);
  std::printf("[%s] pendulum period %.6f s, 2 pi sqrt(l/g) %.6f s, error %.3e\n", GetParam(), period, expected,
              period / expected - 1.0);
  EXPECT_NEAR(period / expected, 1.0, 0.005);
}

// Verifies that a physical pendulum (a sphere on a ball joint at distance d
// above its centre, so it rotates) swings with 2 pi sqrt(I_p / (m g d)),
// I_p = 2/5 m r^2 + m d^2 (parallel axes), to 0.5%.
TEST_P(JointPendulumTest, BallJointPendulumHasThePhysicalPendulumPeriod) {
  const double r = 0.2, d = 0.5, theta0 = 0.05;
  JointSim sim(GetParam());
  const BodyId bob = AddSphere(sim.world, r, kPivot + d * Vec3(std::sin(theta0), 0, -std::cos(theta0)), 0.0);
  AddJoint(sim.world, JointKind::kBall, bob, kWorldBody, kPivot);
  const double period = MeasurePeriod(sim, bob, 10.0);
  const double expected = 2.0 * kPi * std::sqrt((0.4 * r * r + d * d) / (kG * d));
  std::printf("[%s] physical pendulum period %.6f s, expected %.6f s, error %.3e\n", GetParam(), period, expected,
              period / expected - 1.0);
  EXPECT_NEAR(period / expected, 1.0, 0.005);
}

// Verifies that the distance constraint |p - pivot| = l holds to 1e-6 m at
// every step of 10 s of a large (1 rad) swing: the post-stabilisation
// projects the drift away each step.
TEST_P(JointPendulumTest, ConstraintDriftStaysBelowOneMicrometre) {
  const double l = 1.0, theta0 = 1.0;
  JointSim sim(GetParam());
  const BodyId bob = AddSphere(sim.world, 0.05, kPivot + l * Vec3(std::sin(theta0), 0, -std::cos(theta0)), 0.0);
  AddJoint(sim.world, JointKind::kDistance, bob, kWorldBody, kPivot);
  double drift = 0.0;
  while (sim.world.time < 10.0) {
    sim.Step();
    drift = std::max(drift, std::abs((sim.world.Find(bob)->x - kPivot).norm() - l));
  }
  std::printf("[%s] largest distance drift over 10 s: %.3e m\n", GetParam(), drift);
  EXPECT_LT(drift, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Methods, JointPendulumTest,
                         ::testing::Values("impulse", "penalty", "lcp:pgs", "lcp:lemke", "xpbd"));

// The velocity-level methods, whose joint solve keeps the energy (xpbd
// projects positions and loses energy at O(h): xpbd_joint_test.cpp).
class JointEnergyTest : public ::testing::TestWithParam<const char*> {};

// Verifies that a double pendulum (two spheres on distance joints, both arms
// released horizontal: chaotic motion) keeps its energy to 1% over 10 s.
// The error is relative to the energy above the hanging rest state (the
// part that moves, independent of the height datum).
TEST_P(JointEnergyTest, DoublePendulumConservesEnergy) {
  JointSim sim(GetParam());
  const testing::EnergyRecord e = testing::RunDoublePendulum(sim, kPivot, 10.0);
  std::printf("[%s] double pendulum: largest energy error %.3e of %.4f J above rest\n", GetParam(), e.worst,
              e.above_rest);
  EXPECT_LT(e.worst, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Methods, JointEnergyTest,
                         ::testing::Values("impulse", "penalty", "lcp:pgs", "lcp:lemke"));

}  // namespace
}  // namespace contactsim
