// Joint damping and joint Coulomb friction (physics/joint.h) under every
// registered method (a method without joints refuses the world by its
// contract), against the analytic answers: the damped linear oscillator of
// a hinged pendulum, a heavily damped one that stays overdamped, a pendulum
// held by friction below its gravity torque and let go above, and a forced
// slider with damping and friction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/scenario_tolerances.h"

namespace contactsim {
namespace {

using testing::MethodConfig;

constexpr double kMasses[] = {0.1, 1.0, 10.0};  // kg
const Vec3 kPivot(0, 0, 2);                      // m
constexpr double kArm = 1.0;                     // m, pivot to the bob's centre
constexpr double kBobRadius = 0.05;              // m
// Largest error of the damped swing against the linear oscillator, relative
// to its amplitude: the aim is 2%; the sin(q) ~ q error at 0.02 rad is 2.5e-5.
constexpr double kOscillatorTolerance = 0.02;

// A sphere of `mass` hanging kArm from kPivot after turning by `angle`
// about y, on a hinge about y at the pivot (A the bob, B the world), with
// the joint's damping and friction; returns the joint id.
struct Pendulum {
  BodyId bob = 0;
  JointId joint = 0;
  double inertia = 0.0;  // kg m^2 about the axis through the pivot
};

Pendulum AddPendulum(World& world, double mass, double angle, double damping, double friction) {
  Pendulum p;
  const Vec3 arm = Quat(Eigen::AngleAxisd(angle, Vec3::UnitY())) * Vec3(0, 0, -kArm);
  p.bob = testing::AddSphere(world, kBobRadius, kPivot + arm, 0.0);
  RigidBody* bob = world.Find(p.bob);
  bob->SetMass(mass);
  p.inertia = 0.4 * mass * kBobRadius * kBobRadius + mass * kArm * kArm;
  JointSettings s;
  s.kind = JointKind::kHinge;
  s.body_a = p.bob;
  s.body_b = kWorldBody;
  s.anchor = kPivot;
  s.axis = Vec3::UnitY();
  s.damping = damping;
  s.friction = friction;
  p.joint = testing::AddJoint(world, s);
  return p;
}

// Sets the bob swinging about the pivot at `rate` rad/s about y.
void Swing(World& world, BodyId bob, double rate) {
  RigidBody* b = world.Find(bob);
  const Vec3 w = rate * Vec3::UnitY();
  b->SetVelocity(w.cross(b->x - kPivot), w);
}

double Coordinate(const World& world, const Pendulum& p) {
  return JointPosition(*world.FindJoint(p.joint), *world.Find(p.bob), nullptr);
}
double CoordinateRate(const World& world, const Pendulum& p) {
  return JointVelocity(*world.FindJoint(p.joint), *world.Find(p.bob), nullptr);
}

class JointDynamicsTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies that a hinged pendulum with damping c, started from rest
// hanging with a small swing (amplitude 0.02 rad), follows the linear
// damped oscillator q(t) = q'(0) / w_d e^(-zeta w t) sin(w_d t), w^2 =
// m g l / I, zeta = c / (2 I w), within 2% of the amplitude over 5 s
// (zeta 0.05 and 0.3; masses 0.1-10 kg).
TEST_P(JointDynamicsTest, DampedHingeFollowsTheLinearDampedOscillator) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double mass : kMasses) {
    for (const double zeta : {0.05, 0.3}) {
      testing::MethodSim sim(config.method, config.params);
      const double inertia = 0.4 * mass * kBobRadius * kBobRadius + mass * kArm * kArm;
      const double w0 = std::sqrt(mass * testing::kG * kArm / inertia);
      const Pendulum p = AddPendulum(sim.world, mass, 0.0, 2.0 * zeta * w0 * inertia, 0.0);
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      Swing(sim.world, p.bob, 0.02 * w0);
      const double rate0 = CoordinateRate(sim.world, p);
      const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
      const double amplitude = std::abs(rate0) / w0;
      double worst = 0.0;
      while (sim.world.time < 5.0) {
        sim.Step();
        const double t = sim.world.time;
        const double analytic = rate0 / wd * std::exp(-zeta * w0 * t) * std::sin(wd * t);
        worst = std::max(worst, std::abs(Coordinate(sim.world, p) - analytic) / amplitude);
      }
      char id[64];
      std::snprintf(id, sizeof id, "damped hinge m=%g zeta=%g", mass, zeta);
      std::printf("%-10s %-30s worst error %.3e of the amplitude\n", config.label.c_str(), id, worst);
      checks.Expect(id, worst, 0.0, kOscillatorTolerance);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that damping far beyond critical (zeta 100 and 1e5) stays
// stable and overdamped: the swing never grows past its undamped
// amplitude, never overshoots to the other side, and every value stays
// finite (the damper is implicit: its effective mass grows with c h).
TEST_P(JointDynamicsTest, LargeDampingStaysStableAndOverdamped) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double mass : kMasses) {
    for (const double zeta : {100.0, 1e5}) {
      testing::MethodSim sim(config.method, config.params);
      const double inertia = 0.4 * mass * kBobRadius * kBobRadius + mass * kArm * kArm;
      const double w0 = std::sqrt(mass * testing::kG * kArm / inertia);
      const Pendulum p = AddPendulum(sim.world, mass, 0.0, 2.0 * zeta * w0 * inertia, 0.0);
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      Swing(sim.world, p.bob, 0.5 * w0);
      const double sign = CoordinateRate(sim.world, p) > 0.0 ? 1.0 : -1.0;
      const double amplitude = 0.5;  // rad, undamped
      double largest = 0.0, overshoot = 0.0;
      bool finite = true;
      while (sim.world.time < 2.0) {
        sim.Step();
        const double q = sign * Coordinate(sim.world, p);
        finite = finite && std::isfinite(q) && sim.world.Find(p.bob)->x.allFinite();
        largest = std::max(largest, std::abs(q));
        overshoot = std::max(overshoot, -q);
      }
      char id[64];
      std::snprintf(id, sizeof id, "overdamped hinge m=%g zeta=%g", mass, zeta);
      std::printf("%-10s %-34s largest %.3e rad, overshoot %.3e rad, end rate %.3e\n", config.label.c_str(), id,
                  largest, overshoot, CoordinateRate(sim.world, p));
      EXPECT_TRUE(finite) << config.label << " " << id;
      EXPECT_LE(largest, amplitude) << config.label << " " << id;
      checks.Expect(std::string(id) + " overshoot", overshoot, 0.0, 1e-9);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies joint Coulomb friction on a hinge: a pendulum released 0.5 rad
// from hanging, its gravity torque tau = m g l sin(0.5), stays where it is
// (within 1e-6 rad over 2 s) with friction 1.2 tau, and with friction
// 0.8 tau starts to swing at the angular acceleration (tau - f) / I (rate
// after 0.05 s within 2%).
TEST_P(JointDynamicsTest, HingeFrictionHoldsBelowItsTorqueAndYieldsAbove) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  const double angle = 0.5;
  for (const double mass : kMasses) {
    const double tau = mass * testing::kG * kArm * std::sin(angle);
    for (const double ratio : {1.2, 0.8}) {
      testing::MethodSim sim(config.method, config.params);
      const Pendulum p = AddPendulum(sim.world, mass, angle, 0.0, ratio * tau);
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      char id[64];
      std::snprintf(id, sizeof id, "hinge friction m=%g f=%g tau", mass, ratio);
      if (ratio > 1.0) {
        double moved = 0.0;
        while (sim.world.time < 2.0) {
          sim.Step();
          moved = std::max(moved, std::abs(Coordinate(sim.world, p)));
        }
        std::printf("%-10s %-32s held: moved %.3e rad in 2 s\n", config.label.c_str(), id, moved);
        checks.Expect(std::string(id) + " hold", moved, 0.0, 1e-6);
      } else {
        for (int step = 0; step < 12; ++step) sim.Step();
        const double expected = (1.0 - ratio) * tau / p.inertia * sim.world.time;
        const double rate = std::abs(CoordinateRate(sim.world, p));
        std::printf("%-10s %-32s slips: rate %.6f rad/s (%.6f)\n", config.label.c_str(), id, rate, expected);
        checks.Expect(std::string(id) + " slip", rate / expected, 1.0, 0.02);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies a horizontal slider pushed by F = 2 m N/kg along its axis:
// friction 1.5 F holds it (within 1e-9 m over 1 s); friction 0.5 F lets it
// accelerate at (F - f) / m (rate within 1e-6); damping c = 2 m N s/m gives
// v = F / c (1 - e^(-c t / m)) (within 1%: backward Euler's lag).
TEST_P(JointDynamicsTest, SliderFrictionAndDampingFollowTheAnalyticMotion) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double mass : kMasses) {
    const double force = 2.0 * mass;
    struct Case {
      const char* name;
      double friction, damping;
    };
    for (const Case& c : {Case{"hold", 1.5 * force, 0.0}, Case{"slip", 0.5 * force, 0.0},
                          Case{"damped", 0.0, 2.0 * mass}}) {
      testing::MethodSim sim(config.method, config.params);
      const Vec3 p0(0, 0, 1);
      const BodyId block = testing::AddBox(sim.world, Vec3(0.1, 0.15, 0.2), p0, 0.0, 0.5);
      sim.world.Find(block)->SetMass(mass);
      JointSettings s;
      s.kind = JointKind::kPrismatic;
      s.body_a = block;
      s.anchor = p0;
      s.axis = Vec3(-1, -1, 0);  // the world (B) relative to the block: the block's slide along (1, 1, 0)
      s.friction = c.friction;
      s.damping = c.damping;
      const JointId id = testing::AddJoint(sim.world, s);
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      TimedWrench push;
      push.body = block;
      push.force = force * Vec3(1, 1, 0).normalized();
      push.remaining = 10.0;
      sim.world.AddWrench(push);
      double moved = 0.0;
      while (sim.world.time < 1.0) {
        sim.Step();
        moved = std::max(moved, std::abs(JointPosition(*sim.world.FindJoint(id), *sim.world.Find(block), nullptr)));
      }
      const double t = sim.world.time;
      const double rate = JointVelocity(*sim.world.FindJoint(id), *sim.world.Find(block), nullptr);
      const double k = c.damping / mass;
      const double expected = c.damping > 0.0 ? force / c.damping * (1.0 - std::exp(-k * t))
                                              : std::max(0.0, force - c.friction) / mass * t;
      char text[64];
      std::snprintf(text, sizeof text, "slider %s m=%g", c.name, mass);
      std::printf("%-10s %-24s rate %.9f m/s (%.9f), moved %.3e m\n", config.label.c_str(), text, rate, expected,
                  moved);
      if (expected == 0.0) {
        checks.Expect(std::string(text), moved, 0.0, 1e-9);
      } else {
        checks.Expect(std::string(text), rate / expected, 1.0, c.damping > 0.0 ? 0.01 : 1e-6);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, JointDynamicsTest, ::testing::ValuesIn(testing::JointedWorldConfigs()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
