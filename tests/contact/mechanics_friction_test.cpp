// Coulomb friction in every registered contact method (tests/contact/
// method_configs.h) against the analytic answers of rigid-body mechanics,
// for masses 0.1, 1 and 10 kg (friction scales with the normal force, so
// none of these answers depends on the mass):
//  * a box launched at v0 on flat ground stops after d = v0^2 / (2 mu g);
//  * a box on a slope holds when tan(theta) < mu and otherwise slides with
//    a = g (sin(theta) - mu cos(theta));
//  * a sphere rolls down a slope without slipping, a = 5/7 g sin(theta)
//    (I = 2/5 m r^2 about its centre), omega = v / r;
//  * a box with high friction stands below its tipping angle and tips above
//    it: the weight's line leaves the base when tan(theta) > half width /
//    half height.
// dt = 1/240 s, g = 9.81 m/s^2; tolerances in tests/contact/scenario_tolerances.h.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "service/physics/body_settings.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/slope.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2
constexpr double kPi = 3.14159265358979323846;

using testing::MethodConfig;
using Sim = testing::MethodSim;

Eigen::Vector4d Wxyz(const Quat& q) { return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z()); }

// A box of half extents `half` and `mass` standing on a slope tilted by
// `angle` (testing::AddSlope), its bottom face on the slope. Returns its id.
BodyId AddBoxOnSlope(World& world, double angle, double mu, const Vec3& half, double mass, Vec3* downhill) {
  const Quat tilt = testing::AddSlope(world, angle, mu, downhill);
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = half;
  box.mass = mass;
  box.position = half.z() * (tilt * Vec3::UnitZ());
  box.orientation = Wxyz(tilt);
  box.restitution = 0.0;
  box.friction = mu;
  return testing::AddValidBody(world, box);
}

using MassParam = std::tuple<MethodConfig, double>;  // method, mass (kg)

class MechanicsFrictionTest : public ::testing::TestWithParam<MassParam> {
 protected:
  const MethodConfig& config() const { return std::get<0>(GetParam()); }
  double mass() const { return std::get<1>(GetParam()); }
  const testing::ScenarioTolerances& tol() const { return testing::TolerancesOf(config().label); }
};

// Verifies the stopping distance of a 0.2 m cube launched at 2 m/s along x
// with mu = 0.4 after resting 0.2 s: d = v0^2 / (2 mu g) = 0.510 m.
TEST_P(MechanicsFrictionTest, SlidingBoxStopsAfterCoulombDistance) {
  const double mu = 0.4, v0 = 2.0, half = 0.1;
  Sim sim(config().method, config().params);
  testing::AddGround(sim.world, 0.0, mu);
  BodySettings box;
  box.shape = ShapeType::kBox;
  box.half_extents = Vec3::Constant(half);
  box.mass = mass();
  box.position = Vec3(0, 0, half);
  box.restitution = 0.0;
  box.friction = mu;
  const BodyId id = testing::AddValidBody(sim.world, box);
  while (sim.world.time < 0.2) sim.Step();  // rest first: barrier pushes a flush pair apart
  RigidBody& b = *sim.world.Find(id);
  const double x0 = b.x.x();
  b.SetVelocity(Vec3(v0, 0, 0), Vec3::Zero());
  const double stop = v0 / (mu * kG);
  while (sim.world.time < 0.2 + stop + 0.5) sim.Step();
  const double d = sim.world.Find(id)->x.x() - x0, expected = v0 * v0 / (2 * mu * kG);
  std::printf("%-10s slide m %5.1f kg: %.4f m (v0^2 / 2 mu g %.4f, %+.2f%%)\n", config().label.c_str(), mass(), d,
              expected, 100 * (d - expected) / expected);
  testing::MechanicsChecks checks(config().label);
  checks.Expect(testing::CaseId("slide m=%g", mass()), d / expected, 1.0, tol().slide);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies static friction: a 0.2 m cube on a 30 degree slope with
// mu = 0.7 > tan(30) = 0.577 holds; after 0.5 s of settling it moves less
// than the table's bound in 2 s.
TEST_P(MechanicsFrictionTest, BoxHoldsOnSlopeWhenTanThetaBelowMu) {
  Sim sim(config().method, config().params);
  Vec3 downhill;
  const BodyId id = AddBoxOnSlope(sim.world, kPi / 6, 0.7, Vec3::Constant(0.1), mass(), &downhill);
  while (sim.world.time < 0.5) sim.Step();  // penalty sinks to its weight's depth
  const Vec3 x0 = sim.world.Find(id)->x;
  while (sim.world.time < 2.5) sim.Step();
  const double moved = (sim.world.Find(id)->x - x0).norm();
  std::printf("%-10s incline hold m %5.1f kg: moved %.3g m in 2 s\n", config().label.c_str(), mass(), moved);
  testing::MechanicsChecks checks(config().label);
  checks.Expect(testing::CaseId("incline hold m=%g", mass()), moved, 0.0, tol().incline_hold);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies dynamic friction on a slope: with mu = 0.3 on 30 degrees the
// cube slides with a = g (sin 30 - mu cos 30) = 2.356 m/s^2, measured as
// s = v0 t + a t^2 / 2 over the second after 0.1 s of settling.
TEST_P(MechanicsFrictionTest, BoxSlidesDownSlopeWithCoulombAcceleration) {
  const double mu = 0.3, angle = kPi / 6;
  Sim sim(config().method, config().params);
  Vec3 downhill;
  const BodyId id = AddBoxOnSlope(sim.world, angle, mu, Vec3::Constant(0.1), mass(), &downhill);
  const double a = kG * (std::sin(angle) - mu * std::cos(angle));
  while (sim.world.time < 0.1) sim.Step();
  const RigidBody& b = *sim.world.Find(id);
  const Vec3 x0 = b.x;
  const double v0 = b.LinearVelocity().dot(downhill), t0 = sim.world.time;
  while (sim.world.time < t0 + 1.0 - 1e-9) sim.Step();
  const double t = sim.world.time - t0;
  const double s = (b.x - x0).dot(downhill), expected = v0 * t + 0.5 * a * t * t;
  std::printf("%-10s incline slide m %5.1f kg: %.4f m in 1 s (analytic %.4f, %+.2f%%), spin %.2g rad/s\n",
              config().label.c_str(), mass(), s, expected, 100 * (s - expected) / expected,
              b.AngularVelocity().norm());
  EXPECT_LT(b.AngularVelocity().norm(), 1e-2) << config().label;  // slides, does not tumble
  testing::MechanicsChecks checks(config().label);
  checks.Expect(testing::CaseId("incline slide m=%g", mass()), s / expected, 1.0, tol().incline_slide);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies rolling without slipping: a sphere of radius 0.1 m on a 15
// degree slope (mu = 0.5, enough: rolling needs mu >= 2/7 tan(theta) =
// 0.077) covers a t^2 / 2 in 1 s from rest, a = 5/7 g sin(theta), and
// spins at omega = v / r.
TEST_P(MechanicsFrictionTest, SphereRollsDownSlopeWithoutSlipping) {
  const double angle = kPi / 12, mu = 0.5, r = 0.1;
  Sim sim(config().method, config().params);
  Vec3 downhill;
  const Quat tilt = testing::AddSlope(sim.world, angle, mu, &downhill);
  BodySettings ball;
  ball.shape = ShapeType::kSphere;
  ball.radius = r;
  ball.mass = mass();
  ball.position = r * (tilt * Vec3::UnitZ());
  ball.restitution = 0.0;
  ball.friction = mu;
  const BodyId id = testing::AddValidBody(sim.world, ball);
  while (sim.world.time < 1.0 - 1e-9) sim.Step();
  const RigidBody& b = *sim.world.Find(id);
  const double t = sim.world.time, a = 5.0 / 7.0 * kG * std::sin(angle);
  const double s = (b.x - ball.position).dot(downhill), expected = 0.5 * a * t * t;
  const double spin = b.AngularVelocity().norm() * r / b.LinearVelocity().norm();
  std::printf("%-10s roll m %5.1f kg: %.4f m in 1 s (5/7 g sin t^2/2 %.4f, %+.2f%%), omega r / v %.4f\n",
              config().label.c_str(), mass(), s, expected, 100 * (s - expected) / expected, spin);
  testing::MechanicsChecks checks(config().label);
  checks.Expect(testing::CaseId("roll m=%g", mass()), s / expected, 1.0, tol().roll);
  checks.Expect(testing::CaseId("roll spin m=%g", mass()), spin, 1.0, tol().roll);
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsFrictionTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(0.1, 1.0, 10.0)),
                         [](const ::testing::TestParamInfo<MassParam>& info) {
                           return std::get<0>(info.param).label + "_" +
                                  std::to_string(static_cast<int>(std::get<1>(info.param) * 10)) + "hg";
                         });

// method, half width (m), half height (m), degrees from the tipping angle
using TipParam = std::tuple<MethodConfig, double, double, double>;

class MechanicsTippingTest : public ::testing::TestWithParam<TipParam> {};

// Verifies the tipping angle of a box (half width a, half height b, 1 kg)
// standing on a slope with mu = 1.2, too rough for it to slide at these
// angles: it stands when tan(theta) < a / b, its tilt on the slope staying
// within the table's bound over 3 s, and falls on its side (tilt > 45 deg)
// when tan(theta) > a / b, 4 degrees either side.
TEST_P(MechanicsTippingTest, BoxStandsBelowAndTipsAboveItsTippingAngle) {
  const auto& [config, a, b, offset_deg] = GetParam();
  const double critical = std::atan(a / b), angle = critical + offset_deg * kPi / 180;
  Sim sim(config.method, config.params);
  Vec3 downhill;
  const BodyId id = AddBoxOnSlope(sim.world, angle, 1.2, Vec3(a, a, b), 1.0, &downhill);
  const Vec3 normal = downhill.cross(Vec3::UnitY());  // the slope's normal (slope.h)
  double tilt = 0.0;
  while (sim.world.time < 3.0) {
    sim.Step();
    const Vec3 up = sim.world.Find(id)->Rotation().col(2);
    tilt = std::max(tilt, std::acos(std::clamp(up.dot(normal), -1.0, 1.0)));
  }
  std::printf("%-10s tip a/b %.3f at %+.0f deg from %.2f deg: largest tilt %.3g rad\n", config.label.c_str(), a / b,
              offset_deg, critical * 180 / kPi, tilt);
  const std::string id_text = testing::CaseId("tip a/b=%.3g %+g deg", a / b, offset_deg);
  testing::MechanicsChecks checks(config.label);
  if (offset_deg < 0) {
    checks.Expect(id_text, tilt, 0.0, testing::TolerancesOf(config.label).tip_stand);
  } else {
    // tipped: fell past 45 degrees (it may go on tumbling, so at least)
    checks.Expect(id_text, std::min(tilt, kPi / 2), kPi / 2, kPi / 4);
  }
  SKIP_KNOWN_MISSES(checks);
}

std::string TipName(const ::testing::TestParamInfo<TipParam>& info) {
  const auto& [config, a, b, offset] = info.param;
  return config.label + "_" + std::to_string(static_cast<int>(std::round(100 * a / b))) +
         (offset < 0 ? "_Below" : "_Above");
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, MechanicsTippingTest,
                         ::testing::Combine(::testing::ValuesIn(testing::EveryMethodConfig()),
                                            ::testing::Values(0.05, 0.1), ::testing::Values(0.15),
                                            ::testing::Values(-4.0, 4.0)),
                         TipName);

}  // namespace
}  // namespace contactsim
