// Prismatic joints and their limits under every registered method (the
// registry's EveryMethodConfig; a method without joints refuses the world by
// its contract): a slider driven by a constant force accelerates at the
// analytic rate along its axis, keeps its line and its orientation; a
// slider falls onto its lower limit and rests there as on a contact with
// restitution 0; two dynamic bodies on a slider keep their momentum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/scenario_tolerances.h"

namespace contactsim {
namespace {

using testing::MethodConfig;

// m: largest distance of B's anchor from A's line, and rad: largest turn of
// B from its pose, over a run (the projection holds both to round-off).
constexpr double kLineTolerance = 1e-6;
constexpr double kTurnTolerance = 1e-6;
// Relative error of the slide rate against a t: the methods' velocity
// solves are exact for a lone slider, so round-off over a few hundred steps.
constexpr double kRateTolerance = 1e-6;
// m: how far past its limit a slider may sink, or rise after landing.
constexpr double kLimitTolerance = 1e-6;
// Relative drift of the total momentum of two bodies on a free slider.
constexpr double kMomentumTolerance = 1e-9;

constexpr double kMasses[] = {0.1, 1.0, 10.0};  // kg

// A box of the given mass (half extents 0.1, 0.15, 0.2 m: unequal inertia)
// at p, restitution 0.
BodyId AddBlock(World& world, const Vec3& p, double mass) {
  const BodyId id = testing::AddBox(world, Vec3(0.1, 0.15, 0.2), p, 0.0, 0.5);
  world.Find(id)->SetMass(mass);
  return id;
}

// A slider whose coordinate is the displacement of the moving body along
// `axis`: B's along the axis fixed in A, or, with B the world, A's (the
// slide is B's motion relative to A, so the axis is given reversed).
JointSettings Slider(BodyId a, BodyId b, const Vec3& anchor, const Vec3& axis,
                     std::optional<std::pair<double, double>> limits = std::nullopt) {
  JointSettings s;
  s.kind = JointKind::kPrismatic;
  s.body_a = a;
  s.body_b = b;
  s.anchor = anchor;
  s.axis = b == kWorldBody ? Vec3(-axis) : axis;
  s.limits = limits;
  return s;
}

// Distance (m) of B's anchor from A's line, and angle (rad) of B's
// orientation from `q0`, for a slider whose B is the world or not.
double OffLine(const World& world, const Joint& j) {
  const RigidBody* a = world.Find(j.body_a);
  const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
  const Vec3 axis = a->q * j.axis_a;
  const Vec3 d = AnchorWorld(j.anchor_b, b) - AnchorWorld(j.anchor_a, a);
  return (d - d.dot(axis) * axis).norm();
}

double TurnFrom(const Quat& q0, const Quat& q) { return q0.angularDistance(q); }

class PrismaticJointTest : public ::testing::TestWithParam<MethodConfig> {};

// Verifies that a block on a slider to the world, pushed by a constant
// force F across several directions and twisted by a constant torque,
// slides at the rate (F/m + g) . a t (the axis a horizontal, tilted and
// vertical; masses 0.1-10 kg), stays on its line within 1e-6 m and keeps
// its orientation within 1e-6 rad over 1 s.
TEST_P(PrismaticJointTest, ForcedSliderAcceleratesAtForceOverMassAndKeepsLineAndOrientation) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  const Vec3 axes[] = {Vec3(1, 0, 0), Vec3(1, 2, 0).normalized(), Vec3(0.3, -0.4, 0.5).normalized(),
                       Vec3(0, 0, 1)};
  for (const double mass : kMasses) {
    for (const Vec3& axis : axes) {
      testing::MethodSim sim(config.method, config.params);
      const Vec3 p0(0.0, 0.0, 1.0);
      const BodyId block = AddBlock(sim.world, p0, mass);
      JointId id = testing::AddJoint(sim.world, Slider(block, kWorldBody, p0 + Vec3(0.05, 0.0, 0.0), axis));
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      const Vec3 force = mass * Vec3(3.0, -1.0, 2.0);
      TimedWrench push;
      push.body = block;
      push.force = force;
      push.torque = mass * Vec3(0.2, -0.1, 0.3);
      push.remaining = 10.0;
      sim.world.AddWrench(push);
      const Quat q0 = sim.world.Find(block)->q;
      const Joint joint = *sim.world.FindJoint(id);
      double off = 0.0, turn = 0.0;
      for (int step = 0; step < 240; ++step) {
        sim.Step();
        off = std::max(off, OffLine(sim.world, joint));
        turn = std::max(turn, TurnFrom(q0, sim.world.Find(block)->q));
      }
      const RigidBody& b = *sim.world.Find(block);
      const double a_expected = (force / mass + sim.world.gravity).dot(axis);
      const double rate = JointVelocity(joint, b, nullptr);
      const double t = sim.world.time;
      char id_text[96];
      std::snprintf(id_text, sizeof id_text, "slider m=%g axis=(%.2f,%.2f,%.2f)", mass, axis.x(), axis.y(),
                    axis.z());
      std::printf("%-10s %-36s rate %.9f (a t %.9f), off line %.2e m, turned %.2e rad\n", config.label.c_str(),
                  id_text, rate, a_expected * t, off, turn);
      checks.Expect(std::string(id_text) + " rate", rate / (a_expected * t), 1.0, kRateTolerance);
      checks.Expect(std::string(id_text) + " line", off, 0.0, kLineTolerance);
      checks.Expect(std::string(id_text) + " turn", turn, 0.0, kTurnTolerance);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a slider released above its lower limit, vertical or
// inclined 30 degrees, slides down at the rate -g sin(theta) t (within 1e-6
// relative), lands on the limit and
// rests there: it never sinks past the limit by more than 1e-6 m, never
// rises from it after landing (restitution 0: a limit is a contact, not a
// spring), and ends at rest.
TEST_P(PrismaticJointTest, SliderFallsOntoItsLowerLimitAndRestsThere) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  const double lower = -0.3;  // m
  for (const double mass : kMasses) {
    for (const double theta_deg : {90.0, 30.0}) {
      const double theta = theta_deg * M_PI / 180.0;
      testing::MethodSim sim(config.method, config.params);
      const Vec3 p0(0.0, 0.0, 1.0);
      const Vec3 axis(std::cos(theta), 0.0, std::sin(theta));
      const BodyId block = AddBlock(sim.world, p0, mass);
      const JointId id = testing::AddJoint(sim.world, Slider(block, kWorldBody, p0, axis, std::make_pair(lower, 0.5)));
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      const Joint joint = *sim.world.FindJoint(id);
      // until the landing (at t = sqrt(2 |lower| / (g sin)) in the
      // continuum) the rate is -g sin t, exact under any (sub-)step
      const double a = testing::kG * std::sin(theta);
      const double t_land = std::sqrt(2.0 * -lower / a);
      double sink = 0.0, rise = 0.0, free_error = 0.0;
      bool landed = false;
      while (sim.world.time < 1.5) {
        sim.Step();
        const RigidBody& b = *sim.world.Find(block);
        const double s = JointPosition(joint, b, nullptr);
        sink = std::max(sink, lower - s);
        if (landed) rise = std::max(rise, s - lower);
        landed = landed || s <= lower + 1e-9;
        if (sim.world.time < t_land - 2.0 * sim.world.dt) {
          const double t = sim.world.time;
          free_error = std::max(free_error, std::abs(JointVelocity(joint, b, nullptr) + a * t) / (a * t));
        }
      }
      const RigidBody& b = *sim.world.Find(block);
      const double rate = JointVelocity(joint, b, nullptr);
      const double end = JointPosition(joint, b, nullptr);
      char id_text[64];
      std::snprintf(id_text, sizeof id_text, "limit m=%g theta=%g", mass, theta_deg);
      std::printf("%-10s %-26s end %.9f, sank %.2e, rose %.2e, free fall error %.2e, end rate %.2e\n",
                  config.label.c_str(), id_text, end, sink, rise, free_error, rate);
      EXPECT_TRUE(landed) << config.label << " " << id_text;
      checks.Expect(std::string(id_text) + " free slide", free_error, 0.0, 1e-6);
      checks.Expect(std::string(id_text) + " sink", sink, 0.0, kLimitTolerance);
      checks.Expect(std::string(id_text) + " bounce", rise, 0.0, kLimitTolerance);
      checks.Expect(std::string(id_text) + " rest", std::abs(rate), 0.0, 1e-6);
      checks.Expect(std::string(id_text) + " line", OffLine(sim.world, joint), 0.0, kLineTolerance);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that two dynamic blocks on a slider between them, pushed apart
// along the axis by equal and opposite forces without gravity, A moving
// along the axis at first, keep their total momentum (1e-9 relative) and
// separate at the rate
// -a . v_A0 + F (1/m_a + 1/m_b) t; mass ratios up to 100.
TEST_P(PrismaticJointTest, TwoBodySliderConservesMomentum) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double m_a : kMasses) {
    for (const double m_b : {0.1, 10.0}) {
      testing::MethodSim sim(config.method, config.params);
      sim.world.gravity = Vec3::Zero();
      const Vec3 axis = Vec3(1.0, 1.0, 0.5).normalized();
      const BodyId a = AddBlock(sim.world, Vec3(0, 0, 1), m_a);
      const BodyId b = AddBlock(sim.world, Vec3(0, 0, 1) + 0.6 * axis, m_b);
      const Vec3 v0 = -0.3 * axis;  // m/s, A's; B at rest
      sim.world.Find(a)->SetVelocity(v0, Vec3::Zero());
      const JointId id = testing::AddJoint(sim.world, Slider(a, b, Vec3(0, 0, 1) + 0.3 * axis, axis));
      if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
      const Joint joint = *sim.world.FindJoint(id);
      const double f = 2.0;  // N
      for (const auto& [body, sign] : {std::make_pair(a, -1.0), std::make_pair(b, 1.0)}) {
        TimedWrench w;
        w.body = body;
        w.force = sign * f * axis;
        w.remaining = 10.0;
        sim.world.AddWrench(w);
      }
      auto momentum = [&sim, a, b] { return Vec3(sim.world.Find(a)->P + sim.world.Find(b)->P); };
      const Vec3 p0 = momentum();
      double drift = 0.0;
      for (int step = 0; step < 240; ++step) {
        sim.Step();
        drift = std::max(drift, (momentum() - p0).norm() / p0.norm());
      }
      const double rate = JointVelocity(joint, *sim.world.Find(a), sim.world.Find(b));
      const double expected = -axis.dot(v0) + f * (1.0 / m_a + 1.0 / m_b) * sim.world.time;
      char id_text[64];
      std::snprintf(id_text, sizeof id_text, "two-body slider ma=%g mb=%g", m_a, m_b);
      std::printf("%-10s %-32s momentum drift %.2e, rate %.9f (%.9f), off line %.2e\n", config.label.c_str(),
                  id_text, drift, rate, expected, OffLine(sim.world, joint));
      checks.Expect(std::string(id_text) + " momentum", drift, 0.0, kMomentumTolerance);
      checks.Expect(std::string(id_text) + " rate", rate / expected, 1.0, kRateTolerance);
      checks.Expect(std::string(id_text) + " line", OffLine(sim.world, joint), 0.0, kLineTolerance);
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a block far along its rail slides as near it: the rail's
// world anchor 0, 20 or 50 m up the axis (30 degrees below the horizontal)
// from the block, which starts down it at 5 m/s; blocks of 0.1-10 kg and
// half sizes 0.02-0.5 m. Over 2 s the slide rate stays v0 + g sin t
// (1e-6 relative), the block on its line (1e-6 m), and T + V never rises
// above its start (the semi-implicit step only loses energy on a constant
// slope: m (g sin)^2 h^2 / 2 a step) by more than 1e-9 of m g 1 m. Where the
// line rows' lever arm reached the far anchor, the rows of a 0.5 kg plank
// 16 m down its rail pumped energy into it.
TEST_P(PrismaticJointTest, SliderFarAlongItsRailKeepsItsRateAndEnergy) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  const double theta = 30.0 * M_PI / 180.0;
  const Vec3 axis(std::cos(theta), 0.0, -std::sin(theta));  // down the rail
  const double v0 = 5.0;                                     // m/s
  for (const double mass : kMasses) {
    for (const double half : {0.02, 0.1, 0.5}) {
      for (const double far : {0.0, 20.0, 50.0}) {
        testing::MethodSim sim(config.method, config.params);
        const Vec3 p0(0.0, 0.0, 1.0);
        const BodyId block = testing::AddBox(sim.world, Vec3(half, 1.5 * half, 0.5 * half), p0, 0.0, 0.5);
        sim.world.Find(block)->SetMass(mass);
        sim.world.Find(block)->SetVelocity(v0 * axis, Vec3::Zero());
        const JointId id = testing::AddJoint(sim.world, Slider(block, kWorldBody, p0 - far * axis, axis));
        if (testing::RefusedByContract(config, sim.world, testing::ContractOf(config).joints, "joints")) return;
        const Joint joint = *sim.world.FindJoint(id);
        const double e0 = testing::MechanicalEnergy(sim.world);
        double rise = 0.0, off = 0.0;
        while (sim.world.time < 2.0) {
          sim.Step();
          rise = std::max(rise, testing::MechanicalEnergy(sim.world) - e0);
          off = std::max(off, OffLine(sim.world, joint));
        }
        const double expected = v0 + testing::kG * std::sin(theta) * sim.world.time;
        const double rate = JointVelocity(joint, *sim.world.Find(block), nullptr);
        char id_text[64];
        std::snprintf(id_text, sizeof id_text, "far slider m=%g half=%g far=%g", mass, half, far);
        std::printf("%-10s %-34s rate %.9f (%.9f), off line %.2e m, energy rise %.2e J\n", config.label.c_str(),
                    id_text, rate, expected, off, rise);
        checks.Expect(std::string(id_text) + " rate", rate / expected, 1.0, kRateTolerance);
        checks.Expect(std::string(id_text) + " line", off, 0.0, kLineTolerance);
        checks.Expect(std::string(id_text) + " energy", std::max(0.0, rise), 0.0, 1e-9 * mass * testing::kG);
      }
    }
  }
  SKIP_KNOWN_MISSES(checks);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, PrismaticJointTest, ::testing::ValuesIn(testing::JointedWorldConfigs()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
