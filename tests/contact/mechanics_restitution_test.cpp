// Restitution in every registered contact method (tests/contact/
// method_configs.h) against the analytic answers of Newton's impact law,
// v+ = -e v-: a dropped sphere rebounds to e^2 h whatever its mass, and in
// Newton's cradle (equal spheres, e = 1) the strike passes the whole
// momentum to the last sphere and leaves the others at rest. dt = 1/240 s,
// g = 9.81 m/s^2; tolerances in tests/contact/scenario_tolerances.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "service/physics/body_settings.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::MethodConfig;
using Sim = testing::MethodSim;

using BounceParam = std::tuple<MethodConfig, double, double>;  // method, mass (kg), e

class MechanicsBounceTest : public ::testing::TestWithParam<BounceParam> {};

// The first rebound apex (m) of the lowest point of a sphere of radius r
// dropped from h onto a ground of the same restitution e: the highest point
// between the end of the impact (the fall slowed to 1% of the impact speed
// sqrt(2 g h): e = 0 may leave it resting at -0.0 m/s) and the first step
// it falls again (or 1.5 s, for e = 0, where it may never rise).
// A method without restitution in its contract refuses e > 0 (*refused).
double FirstApex(const MethodConfig& config, double mass, double e, double r, double h, bool* refused) {
  Sim sim(config.method, config.params);
  testing::AddGround(sim.world, e, 0.5);
  BodySettings s;
  s.shape = ShapeType::kSphere;
  s.radius = r;
  s.mass = mass;
  s.position = Vec3(0, 0, h + r);
  s.restitution = e;
  s.friction = 0.5;
  const BodyId id = testing::AddValidBody(sim.world, s);
  *refused = testing::RefusedByContract(config, sim.world, e == 0.0 || testing::ContractOf(config).restitution,
                                        "restitution");
  if (*refused) return 0.0;
  const double stopped = -0.01 * std::sqrt(2 * kG * h);  // m/s
  bool reversed = false;
  double apex = 0.0, last_vz = 0.0, reversed_at = 0.0;
  while (sim.world.time < 3.0) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(id);
    const double vz = b.LinearVelocity().z();
    if (!reversed && last_vz < stopped && vz >= stopped) {
      reversed = true;
      reversed_at = sim.world.time;
    }
    if (reversed) {
      apex = std::max(apex, b.x.z() - r);
      if ((vz < 0.0 && last_vz > 0.0) || sim.world.time > reversed_at + 1.5) break;
    }
    last_vz = vz;
  }
  EXPECT_TRUE(reversed) << config.label << " never stopped falling";
  return apex;
}

// Verifies Newton's impact law for masses 0.1, 1 and 10 kg: a sphere of
// 0.1 m radius dropped from 0.9 m rebounds to e^2 h (free flight up and
// down at the same g, so apex / h = (v+ / v-)^2 = e^2).
TEST_P(MechanicsBounceTest, FirstApexIsRestitutionSquaredTimesDropHeight) {
  const auto& [config, mass, e] = GetParam();
  const double h = 0.9, r = 0.1;
  bool refused = false;
  const double ratio = FirstApex(config, mass, e, r, h, &refused) / h;
  if (refused) return;
  std::printf("%-10s bounce m %5.1f kg e %.1f: apex / h %.4f (e^2 %.4f)\n", config.label.c_str(), mass, e, ratio,
              e * e);
  testing::MechanicsChecks checks(config.label);
  checks.Expect(testing::CaseId("bounce m=%g e=%g", mass, e), ratio, e * e, testing::TolerancesOf(config.label).bounce);
  SKIP_KNOWN_MISSES(checks);
}

std::string BounceName(const ::testing::TestParamInfo<BounceParam>& info) {
  const auto& [config, mass, e] = info.param;
  return config.label + "_" + std::to_string(static_cast<int>(mass * 10)) + "hg_e" +
         std::to_string(static_cast<int>(e * 10));
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsBounceTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(0.1, 1.0, 10.0), ::testing::Values(0.0, 0.5, 0.9)),
                         BounceName);

using CradleParam = std::tuple<MethodConfig, int>;  // method, spheres

class MechanicsCradleTest : public ::testing::TestWithParam<CradleParam> {};

// Verifies Newton's cradle without gravity: n equal spheres (e = 1, no
// friction) in a row 2 mm apart, the first struck into the others at v0.
// Momentum and energy conservation with e = 1 on each pair leave only one
// answer for equal masses: the last leaves at v0, the others at rest.
TEST_P(MechanicsCradleTest, StrikePassesTheMomentumToTheLastSphere) {
  const auto& [config, n] = GetParam();
  const double r = 0.05, gap = 2e-3, v0 = 1.0;
  Sim sim(config.method, config.params);
  sim.world.gravity.setZero();
  std::vector<BodyId> balls;
  for (int i = 0; i < n; ++i) {
    const Vec3 p(i * (2 * r + gap) + (i == 0 ? -0.01 : 0.0), 0, 0);
    balls.push_back(testing::AddSphere(sim.world, r, p, 1.0, 0.0, i == 0 ? Vec3(v0, 0, 0) : Vec3::Zero()));
  }
  if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).restitution, "restitution")) return;
  const double p0 = sim.world.Find(balls[0])->P.x();
  while (sim.world.time < 0.25) sim.Step();  // the last one leaves after ~0.02 s
  double others = 0.0, p = 0.0;
  for (int i = 0; i < n; ++i) {
    const RigidBody& b = *sim.world.Find(balls[i]);
    p += b.P.x();
    if (i + 1 < n) others = std::max(others, b.LinearVelocity().norm() / v0);
  }
  const double last = sim.world.Find(balls.back())->LinearVelocity().x() / v0;
  std::printf("%-10s cradle of %d: last %.4f v0, others at most %.4f v0, momentum %+.2e relative\n",
              config.label.c_str(), n, last, others, (p - p0) / p0);
  EXPECT_NEAR(p, p0, 1e-9 * p0) << config.label;  // equal and opposite impulses
  const double tol = testing::TolerancesOf(config.label).cradle;
  testing::MechanicsChecks checks(config.label);
  checks.Expect("cradle n=" + std::to_string(n), std::max(std::abs(last - 1.0), others), 0.0, tol);
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsCradleTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()), ::testing::Values(3, 5)),
                         [](const ::testing::TestParamInfo<CradleParam>& info) {
                           return std::get<0>(info.param).label + "_" + std::to_string(std::get<1>(info.param));
                         });

}  // namespace
}  // namespace contactsim
