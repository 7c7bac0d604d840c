// Compound bodies swept over masses, centres of mass and child counts under
// every registered contact method (method_configs.h), or its contract's
// refusal (docs/physics.md, "Compound bodies under every contact method"):
//  - a row of 2 to 6 feet under a plate, 0.1-10 kg, its centre of mass
//    given or off the plate's centre, dropped 2 cm with restitution 0:
//    its mechanical energy m g z + T never rises above the drop's, and it
//    comes to rest (every point slower than kRestSpeed after kSettle);
//  - a table placed with its four legs exactly touching the ground (four
//    points a leg face) stays at rest and does not spin;
//  - an L on one bottom edge, tilted 0.05 rad below and above its tipping
//    angle atan(d / h) (d, h the centre of mass's distance from the edge
//    along the ground and above it), falls back onto its base below it and
//    tips over the edge above it;
//  - a wheel, a cylinder hull whose frame lies off its axis, rolls down a
//    slope as the same hull as a plain body does: its speed and omega r / v
//    within 1% of the plain body's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "service/physics/body_settings.h"
#include "service/physics/cylinder_hull.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/scenario_tolerances.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

using testing::MethodConfig;

constexpr double kPi = 3.14159265358979323846;
constexpr double kSettle = 2.0;      // s to come to rest
constexpr double kRestSpeed = 1e-3;  // m/s, fastest a resting body's point may move after kSettle
// J per J dropped: the most the mechanical energy may rise above the drop's
// (round-off and the contact's own compliance give back well below it)
constexpr double kEnergyRise = 1e-3;
constexpr double kMasses[] = {0.1, 1.0, 10.0};

ShapePart Box(const Vec3& half, const Vec3& position) {
  ShapePart p;
  p.type = ShapeType::kBox;
  p.half_extents = half;
  p.position = position;
  return p;
}

// n cubic feet of edge 0.04 m along x under a plate 0.02 m thick; the frame's
// origin is at the feet's bottom face centre, so the body rests with it at 0.
std::vector<ShapePart> Feet(int n) {
  const double span = 0.1 * (n - 1);
  std::vector<ShapePart> parts = {Box(Vec3(0.5 * span + 0.04, 0.06, 0.01), Vec3(0, 0, 0.05))};
  for (int k = 0; k < n; ++k) parts.push_back(Box(Vec3(0.02, 0.02, 0.02), Vec3(-0.5 * span + 0.1 * k, 0, 0.02)));
  return parts;
}

// a top 0.4 x 0.3 m on four legs 0.2 m long; the frame's origin at the legs' feet
std::vector<ShapePart> Table() {
  std::vector<ShapePart> parts = {Box(Vec3(0.2, 0.15, 0.015), Vec3(0, 0, 0.215))};
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) parts.push_back(Box(Vec3(0.015, 0.015, 0.1), Vec3(0.17 * sx, 0.12 * sy, 0.1)));
  }
  return parts;
}

BodySettings CompoundSettings(std::vector<ShapePart> parts, double mass, double friction) {
  BodySettings s;
  s.shape = ShapeType::kCompound;
  s.parts = std::move(parts);
  s.mass = mass;
  s.restitution = 0.0;
  s.friction = friction;
  return s;
}

double FastestPoint(const RigidBody& b, double reach) {
  return b.LinearVelocity().norm() + b.AngularVelocity().norm() * reach;
}

double Tilt(const RigidBody& b) {
  const Vec3 up = b.q * Vec3::UnitZ();
  return std::atan2(up.cross(Vec3::UnitZ()).norm(), up.z());
}

// m g z of the centre of mass plus the kinetic energy (J)
double Energy(const World& world, const RigidBody& b) { return b.KineticEnergy() - b.mass * world.gravity.dot(b.x); }

class CompoundSweepTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies kEnergyRise and kRestSpeed for 2-6 feet, three masses, the
// centre of mass at the parts' or off it (explicit, 3 cm along x, 1 cm
// along y, inside the feet's support).
TEST_P(CompoundSweepTest, DroppedFeetNeverGainEnergyAndComeToRest) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const int feet : {2, 3, 4, 6}) {
    for (const bool offset : {false, true}) {
      for (const double mass : kMasses) {
        testing::MethodSim sim(config.method, config.params);
        testing::AddGround(sim.world, 0.0, 0.6);
        BodySettings s = CompoundSettings(Feet(feet), mass, 0.6);
        if (offset) s.center_of_mass = Vec3(0.03, 0.01, 0.04);
        s.position = Vec3(0, 0, 0.02);
        const BodyId id = testing::AddValidBody(sim.world, s);
        if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).compound_bodies, "compound")) {
          return;
        }
        const double e0 = Energy(sim.world, *sim.world.Find(id));
        const double dropped = mass * sim.world.gravity.norm() * 0.02;
        double rise = 0.0, speed = 0.0;
        const int settle = static_cast<int>(std::lround(kSettle / sim.world.dt));
        for (int i = 0; i < settle + 30; ++i) {
          sim.Step();
          const RigidBody& b = *sim.world.Find(id);
          rise = std::max(rise, (Energy(sim.world, b) - e0) / dropped);
          if (i >= settle) speed = std::max(speed, FastestPoint(b, 0.5));
        }
        const std::string name = testing::CaseId("feet n=%g m=%g", feet, mass) + (offset ? " offset" : "");
        std::printf("%-10s %-22s energy rise %+.2e of the drop, speed %.2e m/s\n", config.label.c_str(), name.c_str(),
                    rise, speed);
        checks.Expect(name + " energy", std::max(rise, 0.0), 0.0, kEnergyRise);
        checks.Expect(name + " speed", speed, 0.0, kRestSpeed);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies a table placed on its four legs, each leg's face exactly on the
// ground, stays at rest (every point slower than kRestSpeed at every step
// after the first 0.1 s and at the end) and does not spin (|w_z| r below it).
TEST_P(CompoundSweepTest, TableOnFourTouchingLegsStaysAtRest) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const bool offset : {false, true}) {
    for (const double mass : kMasses) {
      testing::MethodSim sim(config.method, config.params);
      testing::AddGround(sim.world, 0.0, 0.6);
      BodySettings s = CompoundSettings(Table(), mass, 0.6);
      if (offset) s.center_of_mass = Vec3(0.05, -0.04, 0.15);
      const BodyId id = testing::AddValidBody(sim.world, s);
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).compound_bodies, "compound")) {
        return;
      }
      double speed = 0.0, spin = 0.0;
      const int steps = static_cast<int>(std::lround(kSettle / sim.world.dt));
      for (int i = 0; i < steps; ++i) {
        sim.Step();
        const RigidBody& b = *sim.world.Find(id);
        if (i * sim.world.dt < 0.1) continue;  // the compliant methods settle into their springs
        speed = std::max(speed, FastestPoint(b, 0.5));
        spin = std::max(spin, std::abs(b.AngularVelocity().z()) * 0.25);
      }
      const std::string name = testing::CaseId("touching table m=%g", mass) + (offset ? " offset" : "");
      std::printf("%-10s %-28s speed %.2e m/s, spin %.2e m/s\n", config.label.c_str(), name.c_str(), speed, spin);
      checks.Expect(name + " speed", speed, 0.0, kRestSpeed);
      checks.Expect(name + " spin", spin, 0.0, kRestSpeed);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies the L's tipping angle. The L: a base 0.3 x 0.06 x 0.06 m along x
// and a post 0.06 x 0.06 x 0.24 m on its -x end, uniform density; it stands
// on the base's bottom edge at x = +0.15 m, turned about it by theta (the
// -x side lifted). Its centre of mass lies d = 0.15 - x_c from the edge
// along x and h = z_c + 0.03 above it, so it tips past atan(d / h).
TEST_P(CompoundSweepTest, LTipsOverItsEdgeAtTheAnalyticAngle) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  const std::vector<ShapePart> parts = {Box(Vec3(0.15, 0.03, 0.03), Vec3::Zero()),
                                        Box(Vec3(0.03, 0.03, 0.12), Vec3(-0.12, 0, 0.15))};
  // volumes 0.3*0.06*0.06 and 0.06*0.06*0.24: centre of mass (x_c, 0, z_c)
  const double v_base = 0.3 * 0.06 * 0.06, v_post = 0.06 * 0.06 * 0.24;
  const double x_c = v_post * -0.12 / (v_base + v_post), z_c = v_post * 0.15 / (v_base + v_post);
  const double tip = std::atan2(0.15 - x_c, z_c + 0.03);
  const Vec3 edge(0.15, 0, -0.03);  // in the frame
  for (const double mass : kMasses) {
    for (const double delta : {-0.05, 0.05}) {
      testing::MethodSim sim(config.method, config.params);
      testing::AddGround(sim.world, 0.0, 1.0);
      BodySettings s = CompoundSettings(parts, mass, 1.0);
      const Quat turn(Eigen::AngleAxisd(tip + delta, Vec3::UnitY()));
      s.orientation = Eigen::Vector4d(turn.w(), turn.x(), turn.y(), turn.z());
      s.position = -(turn * edge);  // the edge on the ground at the origin
      const BodyId id = testing::AddValidBody(sim.world, s);
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).compound_bodies, "compound")) {
        return;
      }
      for (int i = 0; i < static_cast<int>(std::lround(3.0 / sim.world.dt)); ++i) sim.Step();
      const double tilt = Tilt(*sim.world.Find(id));
      std::printf("%-10s L %4g kg at the tipping angle %.4f %+.2f rad: tilt after 3 s %.3f rad\n",
                  config.label.c_str(), mass, tip, delta, tilt);
      if (delta < 0.0) {
        checks.Expect(testing::CaseId("L m=%g falls back", mass), tilt, 0.0, 0.01);
      } else {
        // over the edge it lands on the post's side, beyond the tipping angle
        checks.Expect(testing::CaseId("L m=%g tips over", mass), std::max(0.0, tip + 0.2 - tilt), 0.0, 0.0);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Largest relative difference of the wheel's rolled ratio (below) from the
// plain hull's: every method measured within 8e-4 (xpbd; lemke 2e-4,
// the others 0) but penalty (a known miss, scenario_tolerances.h).
constexpr double kRolledMatch = 5e-3;

// The wheel's speed after 1 s on a 10 degree slope (gravity turned about y
// instead of the ground), omega r / v then, and the angle it turned times r
// over the distance it travelled (1 when it rolls without slipping, for
// the circumscribed radius r; 0.9993 for the 71 sides, whose flats roll
// 2 r sin(pi / n) a side of 2 pi / n rad).
struct Roll {
  double speed = 0.0;
  double ratio = 0.0;
  double rolled = 0.0;
};

Roll RollWheel(const MethodConfig& config, bool compound, double mass, bool* refused) {
  constexpr double kRadius = 0.1, kSlope = 10.0 * kPi / 180.0;
  testing::MethodSim sim(config.method, config.params);
  sim.world.gravity = 9.81 * Vec3(std::sin(kSlope), 0, -std::cos(kSlope));
  testing::AddGround(sim.world, 0.0, 0.8);
  const Quat axis_y(Eigen::AngleAxisd(0.5 * kPi, Vec3::UnitX()));  // the hull's z axis along y
  const std::vector<Vec3> points = CylinderPoints(kRadius, 0.05, CylinderSides());
  BodySettings s;
  s.mass = mass;
  s.restitution = 0.0;
  s.friction = 0.8;
  if (compound) {
    ShapePart wheel;
    wheel.type = ShapeType::kConvex;
    wheel.points = points;
    wheel.position = Vec3(0.05, 0.02, -0.03);  // the frame off the wheel's axis
    wheel.orientation = axis_y;
    s.shape = ShapeType::kCompound;
    s.parts = {wheel};
    s.position = Vec3(-0.05, -0.02, kRadius + 0.03);
  } else {
    s.shape = ShapeType::kConvex;
    s.points = points;
    s.orientation = Eigen::Vector4d(axis_y.w(), axis_y.x(), axis_y.y(), axis_y.z());
    s.position = Vec3(0, 0, kRadius);
  }
  const BodyId id = testing::AddValidBody(sim.world, s);
  *refused = testing::RefusedByContract(config, sim.world, !compound || testing::ContractOf(config).compound_bodies,
                                        "compound");
  if (*refused) return {};
  const double x0 = sim.world.Find(id)->x.x();
  double turned = 0.0;  // rad about y, the angle the wheel rolled through
  for (int i = 0; i < static_cast<int>(std::lround(1.0 / sim.world.dt)); ++i) {
    sim.Step();
    turned += sim.world.Find(id)->AngularVelocity().y() * sim.world.dt;
  }
  const RigidBody& b = *sim.world.Find(id);
  return {b.LinearVelocity().x(), b.AngularVelocity().y() * kRadius / b.LinearVelocity().x(),
          turned * kRadius / (b.x.x() - x0)};
}

// Verifies the off-axis wheel rolls as the plain hull: its speed within 1%
// of the plain hull's and the angle it turned per distance within
// kRolledMatch. (A 71-sided hull rolls with a bump at every side, and
// omega r / v at an instant of it is not 1: the methods measured
// 0.968-1.026 for either body at 1 s, and where the two bodies' speeds
// differ a little, as under lemke, whose pivots pick among the dependent
// corners of each flat, the instant falls at another phase of the bump:
// 0.968 against 0.988 at 10 kg, whose rolled ratios agree to 1e-4.)
TEST_P(CompoundSweepTest, OffAxisWheelRollsAsThePlainHull) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double mass : kMasses) {
    bool refused = false;
    const Roll plain = RollWheel(config, false, mass, &refused);
    const Roll wheel = RollWheel(config, true, mass, &refused);
    if (refused) return;
    std::printf("%-10s wheel %4g kg: speed %.4f m/s (plain hull %.4f), omega r / v %.4f (plain hull %.4f), "
                "rolled %.4f (plain hull %.4f)\n",
                config.label.c_str(), mass, wheel.speed, plain.speed, wheel.ratio, plain.ratio, wheel.rolled,
                plain.rolled);
    checks.Expect(testing::CaseId("wheel m=%g speed", mass), wheel.speed / plain.speed, 1.0, 0.01);
    checks.Expect(testing::CaseId("wheel m=%g rolling", mass), wheel.rolled / plain.rolled, 1.0, kRolledMatch);
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, CompoundSweepTest, ::testing::ValuesIn(testing::EveryMethodConfig()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
