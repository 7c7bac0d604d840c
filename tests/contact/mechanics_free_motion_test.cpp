// Motion without contact in every registered contact method (tests/contact/
// method_configs.h): each method owns its step and its integrator, so each
// is checked against the closed forms of free and jointed motion.
//  * A pendulum (a sphere on a ball joint or a hinge) swings with the
//    physical pendulum's period T = 2 pi sqrt(I_pivot / (m g L)),
//    I_pivot = m (L^2 + 2/5 r^2), times 1 + theta0^2 / 16 for the amplitude;
//    on a distance joint (a point pendulum) I_pivot = m L^2.
//    A method whose contract has no joints (method_contract.h) must refuse
//    the world with FAILED_PRECONDITION instead of stepping it.
//  * An asymmetric box spinning in zero gravity keeps |L| and its kinetic
//    energy (Euler's equations conserve both).
// dt = 1/240 s, g = 9.81 m/s^2; tolerances in tests/contact/scenario_tolerances.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "service/physics/body_settings.h"
#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kPi = 3.14159265358979323846;

using testing::kG;
using testing::MethodConfig;
using Sim = testing::MethodSim;

using PendulumParam = std::tuple<MethodConfig, JointKind>;

class MechanicsPendulumTest : public ::testing::TestWithParam<PendulumParam> {};

// Verifies the period of a sphere (r = 0.2 m) whose centre hangs L = 0.5 m
// below a ball joint or a hinge (axis y), released at theta0 = 0.1 rad,
// against the physical pendulum's; on a distance joint through its centre
// it does not rotate, a point pendulum: I_pivot = m L^2 (its spin adds 6.4%
// to I_pivot on the other two joints, so the two answers are told apart).
// Measured over six periods (testing::MeasurePeriod).
TEST_P(MechanicsPendulumTest, PeriodIsThePhysicalPendulums) {
  const auto& [config, kind] = GetParam();
  const double r = 0.2, l = 0.5, theta0 = 0.1;
  const Vec3 pivot(0, 0, 2);
  Sim sim(config.method, config.params);
  const BodyId bob = testing::AddSphere(sim.world, r, pivot + l * Vec3(std::sin(theta0), 0, -std::cos(theta0)), 0.0);
  const double spin_inertia = kind == JointKind::kDistance ? 0.0 : 0.4 * r * r;  // per unit mass, m^2
  if (kind == JointKind::kHinge) {
    testing::AddHinge(sim.world, bob, kWorldBody, pivot, Vec3::UnitY());
  } else {
    testing::AddJoint(sim.world, kind, bob, kWorldBody, pivot);
  }
  if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
  const double period = 2 * kPi * std::sqrt((l * l + spin_inertia) / (kG * l)) * (1 + theta0 * theta0 / 16);
  const double measured = testing::MeasurePeriod(sim, bob, 6.25 * period);
  std::printf("%-10s pendulum (%s): period %.5f s, analytic %.5f s (%+.3f%%)\n", config.label.c_str(),
              JointKindName(kind), measured, period, 100 * (measured - period) / period);
  testing::MechanicsChecks checks(config.label);
  checks.Expect(std::string("pendulum ") + JointKindName(kind), measured / period, 1.0,
                testing::TolerancesOf(config.label).pendulum);
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsPendulumTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(JointKind::kDistance, JointKind::kBall,
                                                              JointKind::kHinge)),
                         [](const ::testing::TestParamInfo<PendulumParam>& info) {
                           return std::get<0>(info.param).label + "_" + JointKindName(std::get<1>(info.param));
                         });

class MechanicsFreeRotationTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies torque-free rotation: a box of half extents 0.05 x 0.1 x 0.2 m
// (three distinct moments) spinning at (1, 1, 1) rad/s in zero gravity
// keeps |L| and its kinetic energy over 10 s, to the table's bound at every
// step, and does not move.
TEST_P(MechanicsFreeRotationTest, KeepsAngularMomentumAndEnergy) {
  const MethodConfig& config = GetParam();
  Sim sim(config.method, config.params);
  sim.world.gravity.setZero();
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3(0.05, 0.1, 0.2);
  s.angular_velocity = Vec3(1, 1, 1);
  const BodyId id = testing::AddValidBody(sim.world, s);
  const double l0 = sim.world.Find(id)->L.norm(), e0 = KineticEnergy(sim.world);
  double dl = 0.0, de = 0.0;
  while (sim.world.time < 10.0) {
    sim.Step();
    dl = std::max(dl, std::abs(sim.world.Find(id)->L.norm() - l0) / l0);
    de = std::max(de, std::abs(KineticEnergy(sim.world) - e0) / e0);
  }
  std::printf("%-10s free rotation 10 s: |L| drift %.3g, energy drift %.3g (relative, worst step)\n",
              config.label.c_str(), dl, de);
  EXPECT_LT(sim.world.Find(id)->x.norm(), 1e-9) << config.label;
  const double tol = testing::TolerancesOf(config.label).rotation;
  testing::MechanicsChecks checks(config.label);
  checks.Expect("rotation", std::max(dl, de), 0.0, tol);
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsFreeRotationTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
