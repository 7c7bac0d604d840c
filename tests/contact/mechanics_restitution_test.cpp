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
#include <ostream>
#include <string>
#include <tuple>
#include <vector>

#include "service/physics/body_settings.h"
#include "tests/contact/line_impacts.h"
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

// A body struck into a row of touching or nearly touching bodies of its
// kind and mass on a line, without gravity: the striker and the row `gap`
// apart, the striker at v0 along +x (MechanicsStruckRowTest). The strike is
// head-on, so friction between the bodies must not change the outcome.
struct RowCase {
  ShapeType shape = ShapeType::kSphere;  // spheres of radius 0.05 m, or cubes of half size 0.05 m
  int n = 3;                             // bodies in the row, besides the striker
  double gap = 0.0;                      // m, between neighbours and before the striker
  double mass = 1.0;                     // kg, each
  double v0 = 1.0;                       // m/s
  double e = 1.0;
  double friction = 0.0;                 // Coulomb coefficient of every body
  const char* name = "row";              // the case's name prefix ("cradle" for the classic one)
};

// The case's name as kKnownMisses lists it: "row sphere n=3 gap=0.0001 e=0.5",
// with " mu=0.5" after it when the bodies have friction.
std::string RowCaseId(const RowCase& c) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s %s n=%d gap=%g e=%g", c.name, c.shape == ShapeType::kSphere ? "sphere" : "cube",
                c.n, c.gap, c.e);
  std::string id = buf;
  if (c.friction > 0.0) id += testing::CaseId(" mu=%g", c.friction);
  return id;
}

std::ostream& operator<<(std::ostream& os, const RowCase& c) {
  return os << RowCaseId(c) << " m=" << c.mass << " v0=" << c.v0;
}

constexpr double kRowHalf = 0.05;  // m, sphere radius and cube half size
constexpr double kRowSeconds = 0.1;  // s: a 6-row at 0.5 m/s settles in a few ms, penalty's pairs in ~4 ms each

BodyId AddRowBody(World& world, const RowCase& c, double x, double v) {
  BodySettings s;
  s.shape = c.shape;
  s.radius = kRowHalf;
  s.half_extents = Vec3::Constant(kRowHalf);
  s.mass = c.mass;
  s.position = Vec3(x, 0, 0);
  s.linear_velocity = Vec3(v, 0, 0);
  s.restitution = c.e;
  s.friction = c.friction;
  return testing::AddValidBody(world, s);
}

// Total linear momentum along x (kg m/s) of `ids`.
double MomentumX(const World& world, const std::vector<BodyId>& ids) {
  double p = 0.0;
  for (BodyId id : ids) p += world.Find(id)->P.x();
  return p;
}

// Strikes the row and checks the outcome against StruckLineVelocities
// (line_impacts.h): momentum to round-off (scenario_tolerances.h; equal and opposite
// impulses), each body's velocity within the method's cradle tolerance of
// v0, and with e = 1 the kinetic energy within 1%. A method whose contract
// lacks restitution must refuse e > 0; with e = 0 only its momentum is
// checked.
void StrikeRow(const MethodConfig& config, const RowCase& c) {
  Sim sim(config.method, config.params);
  sim.world.gravity.setZero();
  std::vector<BodyId> ids;
  const double pitch = 2 * kRowHalf + c.gap;
  for (int i = 0; i <= c.n; ++i) ids.push_back(AddRowBody(sim.world, c, i * pitch, i == 0 ? c.v0 : 0.0));
  if (testing::RefusedByContract(config, sim.world, c.e == 0.0 || testing::ContractOf(config).restitution,
                                 "restitution")) {
    return;
  }
  const double p0 = MomentumX(sim.world, ids), ke0 = KineticEnergy(sim.world);
  while (sim.world.time < kRowSeconds) sim.Step();
  const std::vector<double> expected = testing::StruckLineVelocities(c.n + 1, c.v0, c.e);
  double worst = 0.0;
  std::string velocities;
  for (int i = 0; i <= c.n; ++i) {
    const Vec3 v = sim.world.Find(ids[i])->LinearVelocity();
    worst = std::max(worst, (v - Vec3(expected[i], 0, 0)).norm() / c.v0);
    char buf[48];
    std::snprintf(buf, sizeof buf, " %+.4f(%+.4f)", v.x() / c.v0, expected[i] / c.v0);
    velocities += buf;
  }
  const double p = MomentumX(sim.world, ids), ke = KineticEnergy(sim.world) / ke0;
  const std::string id = RowCaseId(c);
  std::printf("%-10s %s m %g v0 %g: v / v0 (analytic)%s; worst %.2e, momentum %+.1e, energy %.4f\n",
              config.label.c_str(), id.c_str(), c.mass, c.v0, velocities.c_str(), worst, (p - p0) / p0, ke);
  testing::MechanicsChecks checks(config.label);
  checks.Expect(id + " momentum", (p - p0) / p0, 0.0, testing::TolerancesOf(config.label).momentum);
  if (c.e == 1.0) checks.Expect(id + " energy", ke, 1.0, 0.01);
  // a method without restitution in its contract (barrier) promises no
  // impact law, not even e = 0's: only what every impact keeps is checked
  if (testing::ContractOf(config).restitution) {
    checks.Expect(id, worst, 0.0, testing::TolerancesOf(config.label).cradle);
  }
  SKIP_KNOWN_MISSES(checks);
}

using CradleParam = std::tuple<MethodConfig, int>;  // method, spheres

class MechanicsCradleTest : public ::testing::TestWithParam<CradleParam> {};

// Verifies Newton's cradle without gravity: n equal spheres (e = 1, no
// friction) in a row 2 mm apart, the first struck into the others at v0.
// Momentum and energy conservation with e = 1 on each pair leave only one
// answer for equal masses: the last leaves at v0, the others at rest.
TEST_P(MechanicsCradleTest, StrikePassesTheMomentumToTheLastSphere) {
  const auto& [config, n] = GetParam();
  RowCase c;
  c.n = n - 1;
  c.gap = 2e-3;
  c.name = "cradle";
  StrikeRow(config, c);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsCradleTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()), ::testing::Values(3, 5)),
                         [](const ::testing::TestParamInfo<CradleParam>& info) {
                           return std::get<0>(info.param).label + "_" + std::to_string(std::get<1>(info.param));
                         });

// The rows of the family: spheres and cubes, rows of 2 to 6, touching and
// 0.1 mm apart, e = 1, 0.5 and 0; the masses (0.1, 1, 10 kg) and strike
// speeds (0.5, 2, 5 m/s) take turns along the list, so that each shape, row
// and e meets several of them without the whole product.
std::vector<RowCase> RowCases() {
  const double masses[] = {0.1, 1.0, 10.0}, speeds[] = {0.5, 2.0, 5.0};
  std::vector<RowCase> cases;
  int k = 0;
  // first the frictionless rows, then the same rows with friction between
  // the bodies (mu 0.5 and 1 in turn)
  for (bool friction : {false, true}) {
    for (ShapeType shape : {ShapeType::kSphere, ShapeType::kBox}) {
      for (int n = 2; n <= 6; ++n) {
        for (double gap : {0.0, 1e-4}) {
          for (double e : {1.0, 0.5, 0.0}) {
            RowCase c;
            c.shape = shape;
            c.n = n;
            c.gap = gap;
            c.e = e;
            if (!friction) {
              // e = 0 falls on every third k: it takes the masses in turn along the rows
              c.mass = masses[(e == 0.0 ? k / 3 : k) % 3];
              c.v0 = speeds[(k / 3 + k) % 3];
            } else {
              // each e meets every mass and speed and both coefficients along the rows
              c.friction = k % 2 == 0 ? 0.5 : 1.0;
              c.mass = masses[(k + k / 3) % 3];
              c.v0 = speeds[(k / 3) % 3];
            }
            cases.push_back(c);
            ++k;
          }
        }
      }
    }
  }
  return cases;
}

using RowParam = std::tuple<MethodConfig, RowCase>;

class MechanicsStruckRowTest : public ::testing::TestWithParam<RowParam> {};

// Verifies restitution across simultaneous contacts: a sphere or cube struck
// into a row of 2 to 6 of its kind, touching or 0.1 mm apart, leaves the
// velocities of one-at-a-time impacts (line_impacts.h: with e = 1 the last
// leaves at v0 and the others rest; e = 0 moves all at v0 / (n + 1)), keeps
// the momentum to round-off and, with e = 1, the kinetic energy to 1%.
TEST_P(MechanicsStruckRowTest, RowLeavesWithTheVelocitiesOfOneImpactAtATime) {
  const auto& [config, c] = GetParam();
  StrikeRow(config, c);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsStruckRowTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::ValuesIn(RowCases())),
                         [](const ::testing::TestParamInfo<RowParam>& info) {
                           const RowCase& c = std::get<1>(info.param);
                           return std::get<0>(info.param).label + "_" +
                                  (c.shape == ShapeType::kSphere ? "sphere" : "cube") + std::to_string(c.n) +
                                  (c.gap > 0.0 ? "_apart" : "_touching") + "_e" +
                                  std::to_string(static_cast<int>(c.e * 10)) +
                                  (c.friction > 0.0 ? "_mu" + std::to_string(static_cast<int>(c.friction * 10)) : "");
                         });

using RackParam = std::tuple<MethodConfig, double, double>;  // method, e, mass (kg)

class MechanicsRackTest : public ::testing::TestWithParam<RackParam> {};

// Verifies a break shot: a cue ball struck at 3 m/s into a touching
// triangle of 15 balls of its mass (0.1 kg to 10 kg), without gravity or
// friction. Which ball leaves how fast depends on the order of many
// simultaneous impacts, so only what every order keeps is checked: the
// momentum to round-off, and with e = 1 the kinetic energy to 1% (every
// impact of e = 1 keeps it); with e < 1 no energy may appear.
TEST_P(MechanicsRackTest, BreakKeepsMomentumAndEnergy) {
  const auto& [config, e, mass] = GetParam();
  const double r = 0.05, v0 = 3.0;
  Sim sim(config.method, config.params);
  sim.world.gravity.setZero();
  RowCase c;
  c.mass = mass;
  c.e = e;
  std::vector<BodyId> ids{AddRowBody(sim.world, c, -5e-3, v0)};
  for (int row = 0; row < 5; ++row) {
    for (int j = 0; j <= row; ++j) {
      BodySettings s;
      s.shape = ShapeType::kSphere;
      s.radius = r;
      s.mass = mass;
      s.position = Vec3(2 * r + row * r * std::sqrt(3.0), (j - 0.5 * row) * 2 * r, 0);
      s.restitution = e;
      s.friction = 0.0;
      ids.push_back(testing::AddValidBody(sim.world, s));
    }
  }
  if (testing::RefusedByContract(config, sim.world, e == 0.0 || testing::ContractOf(config).restitution,
                                 "restitution")) {
    return;
  }
  const double p0 = MomentumX(sim.world, ids), ke0 = KineticEnergy(sim.world);
  while (sim.world.time < kRowSeconds) sim.Step();
  Vec3 p = Vec3::Zero();
  for (BodyId id : ids) p += sim.world.Find(id)->P;
  const double ke = KineticEnergy(sim.world) / ke0;
  std::printf("%-10s rack e %.1f m %g: momentum %+.1e (sideways %.1e), energy %.4f\n", config.label.c_str(), e, mass,
              (p.x() - p0) / p0, p.tail<2>().norm() / p0, ke);
  const std::string id = testing::CaseId("rack e=%g", e);
  testing::MechanicsChecks checks(config.label);
  checks.Expect(id + " momentum", (p - Vec3(p0, 0, 0)).norm() / p0, 0.0, testing::TolerancesOf(config.label).momentum);
  if (e == 1.0) {
    checks.Expect(id + " energy", ke, 1.0, 0.01);
  } else {
    checks.Expect(id + " energy", std::max(ke, 1.0), 1.0, 1e-9);
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsRackTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(1.0, 0.5, 0.0), ::testing::Values(0.1, 10.0)),
                         [](const ::testing::TestParamInfo<RackParam>& info) {
                           return std::get<0>(info.param).label + "_e" +
                                  std::to_string(static_cast<int>(std::get<1>(info.param) * 10)) + "_" +
                                  std::to_string(static_cast<int>(std::get<2>(info.param) * 10)) + "hg";
                         });

}  // namespace
}  // namespace contactsim
