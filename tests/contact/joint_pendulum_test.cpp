// Pendulums through the contact methods that honour joints (impulse,
// penalty, lcp with both solvers, xpbd): the constraint itself and energy
// (xpbd's energy: xpbd_joint_test.cpp). Their periods, point and physical,
// are the mechanics suite's (mechanics_free_motion_test.cpp).
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

class JointPendulumTest : public ::testing::TestWithParam<const char*> {};

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
