// Resting contact in every registered contact method (tests/contact/
// method_configs.h): what statics answers exactly.
//  * The ground carries a resting box's weight: the normal values the method
//    reports (forces, or impulses over dt, ContactMethod::ValueKind) sum to
//    m g, for masses 0.1 to 10 kg.
//  * Stacks of 8 and 20 exactly aligned 0.2 m cubes stand for 10 s: every
//    force is vertical, so no cube has a reason to move sideways, and the
//    top keeps its height.
// dt = 1/240 s, g = 9.81 m/s^2; tolerances in tests/contact/scenario_tolerances.h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
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

using MassParam = std::tuple<MethodConfig, double>;  // method, mass (kg)

class MechanicsRestingForceTest : public ::testing::TestWithParam<MassParam> {};

// The normal force (N) the step's contacts on body `id` carry, as reported:
// impulse methods report N s per step, so their sum is divided by dt.
double NormalForceOn(const Sim& sim, BodyId id) {
  double sum = 0.0;
  for (const Contact& c : sim.contacts) {
    if (c.id_a == id || c.id_b == id) sum += c.normal_value;
  }
  return sim.method->ValueKind() == ContactValueKind::kImpulse ? sum / sim.world.dt : sum;
}

// Verifies that the ground carries a resting 0.2 m cube's weight: after 1 s
// of settling, the reported normal force averaged over the next second is
// m g, and no single step strays by more than the table's bound either.
TEST_P(MechanicsRestingForceTest, ReportedNormalForceEqualsWeight) {
  const auto& [config, mass] = GetParam();
  Sim sim(config.method, config.params);
  testing::AddGround(sim.world, 0.0, 0.5);
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = Vec3::Constant(0.1);
  box.mass = mass;
  box.position = Vec3(0, 0, 0.1);
  box.restitution = 0.0;
  const BodyId id = testing::AddValidBody(sim.world, box);
  while (sim.world.time < 1.0) sim.Step();
  double sum = 0.0, worst = 0.0;
  int steps = 0;
  const double weight = mass * kG;
  while (sim.world.time < 2.0) {
    sim.Step();
    const double f = NormalForceOn(sim, id);
    sum += f;
    worst = std::max(worst, std::abs(f - weight) / weight);
    ++steps;
  }
  const double mean = sum / steps / weight;
  std::printf("%-10s resting force m %5.1f kg: mean %.6f m g, worst step %.3g off\n", config.label.c_str(), mass, mean,
              worst);
  const std::string id_text = testing::CaseId("resting force m=%g", mass);
  const double tol = testing::TolerancesOf(config.label).resting_force;
  testing::MechanicsChecks checks(config.label);
  checks.Expect(id_text + " mean", mean, 1.0, tol);
  checks.Expect(id_text + " worst step", worst, 0.0, tol);
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsRestingForceTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(0.1, 1.0, 10.0)),
                         [](const ::testing::TestParamInfo<MassParam>& info) {
                           return std::get<0>(info.param).label + "_" +
                                  std::to_string(static_cast<int>(std::get<1>(info.param) * 10)) + "hg";
                         });

using StackParam = std::tuple<MethodConfig, int>;  // method, cubes

class MechanicsAlignedStackTest : public ::testing::TestWithParam<StackParam> {};

// How an aligned stack stood: the top cube's height change at the end and
// the largest sideways displacement of any cube at any step (m).
struct StackStand {
  double height = 0.0, drift = 0.0;
};

// Stacks n exactly aligned cubes of half size `half` (mass `mass`, or the
// default density's when unset; mu 0.5, e = 0) touching on the ground and
// steps `seconds` under `config`.
StackStand RunAlignedStack(const MethodConfig& config, int n, double half, std::optional<double> mass,
                           double seconds) {
  Sim sim(config.method, config.params);
  testing::AddGround(sim.world, 0.0, 0.5);
  std::vector<BodyId> cubes;
  for (int i = 0; i < n; ++i) {
    BodySettings s;
    s.shape = ShapeType::kBox;
    s.half_extents = Vec3::Constant(half);
    s.position = Vec3(0, 0, half * (1 + 2 * i));
    s.mass = mass;
    s.friction = 0.5;
    s.restitution = 0.0;
    cubes.push_back(testing::AddValidBody(sim.world, s));
  }
  const double top0 = sim.world.Find(cubes.back())->x.z();
  StackStand stand;
  while (sim.world.time < seconds) {
    sim.Step();
    for (BodyId id : cubes) stand.drift = std::max(stand.drift, sim.world.Find(id)->x.head<2>().norm());
  }
  stand.height = std::abs(sim.world.Find(cubes.back())->x.z() - top0);
  return stand;
}

// Verifies that a stack of n exactly aligned 0.2 m cubes (8 kg each, mu 0.5,
// e = 0) placed touching stands for 10 s (the table's horizon, shorter for a
// method too slow for it): the top cube's height at the end differs from its
// start by less than the table's bound, and no cube moves sideways by more
// than its bound at any step.
TEST_P(MechanicsAlignedStackTest, StandsWithoutDriftingOrSinking) {
  const auto& [config, n] = GetParam();
  const testing::ScenarioTolerances& tol = testing::TolerancesOf(config.label);
  const double seconds = n == 8 ? tol.stack8_seconds : tol.stack20_seconds;
  const StackStand stand = RunAlignedStack(config, n, 0.1, std::nullopt, seconds);
  std::printf("%-10s stack of %2d, %.1f s: top height off by %.3g m at the end, sideways drift %.3g m at most\n",
              config.label.c_str(), n, seconds, stand.height, stand.drift);
  const std::string id = "stack n=" + std::to_string(n);
  testing::MechanicsChecks checks(config.label);
  checks.Expect(id + " height", stand.height, 0.0, tol.stack_height);
  checks.Expect(id + " drift", stand.drift, 0.0, tol.stack_drift);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies the 8-stack at other cube sizes (0.04, 0.1 and 0.3 m) and masses
// (0.1 and 10 kg), with the same bounds over 5 s (a third of the table's
// horizon for a method that runs it shorter). An aligned stack is symmetric
// to round-off; before the box manifold kept flush faces' corners, whether
// round-off broke the symmetry decided whether a stack leaned (lcp: 0.2 m
// cubes 1e-13 m, 0.1 m cubes 0.86 mm).
class MechanicsAlignedStackSweepTest : public ::testing::TestWithParam<MethodConfig> {};

TEST_P(MechanicsAlignedStackSweepTest, StandsAtEverySizeAndMass) {
  const MethodConfig& config = GetParam();
  const testing::ScenarioTolerances& tol = testing::TolerancesOf(config.label);
  const double seconds = tol.stack8_seconds >= 10.0 ? 5.0 : tol.stack8_seconds / 3.0;
  testing::MechanicsChecks checks(config.label);
  for (const double half : {0.02, 0.05, 0.15}) {
    for (const double mass : {0.1, 10.0}) {
      const StackStand stand = RunAlignedStack(config, 8, half, mass, seconds);
      const std::string id = testing::CaseId("stack n=8 size=%g m=%g", 2.0 * half, mass);
      std::printf("%-10s %s, %.1f s: top height off by %.3g m, sideways drift %.3g m at most\n",
                  config.label.c_str(), id.c_str(), seconds, stand.height, stand.drift);
      checks.Expect(id + " height", stand.height, 0.0, tol.stack_height);
      checks.Expect(id + " drift", stand.drift, 0.0, tol.stack_drift);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsAlignedStackTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(8, 20)),
                         [](const ::testing::TestParamInfo<StackParam>& info) {
                           return std::get<0>(info.param).label + "_" + std::to_string(std::get<1>(info.param));
                         });

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsAlignedStackSweepTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         [](const ::testing::TestParamInfo<MethodConfig>& info) { return info.param.label; });

}  // namespace
}  // namespace contactsim
