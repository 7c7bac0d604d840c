// Joint actuators (physics/joint_actuator.h: an implicit PD drive with an
// exact effort clamp, a velocity limit on its target rate, a feed-forward
// effort) under every registered method (a method without joints refuses
// the world by its contract), against the analytic answers: the
// mass-spring-damper step response of a rotor, a pendulum held against
// gravity, a saturated drive as a constant torque, a very stiff drive,
// velocity and torque control, a slider holding its weight, the wrapped
// error of a continuous hinge, refused values, and a two-finger gripper
// lifting a box.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "tests/contact/joint_test_util.h"
#include "tests/contact/method_configs.h"
#include "tests/contact/scenario_tolerances.h"

namespace contactsim {
namespace {

using testing::MethodConfig;

// A rotor: a sphere of `inertia` about every axis (mass 1 kg, so that
// gravity, which the hinge carries, plays no part) hinged to the world at
// its centre about the vertical. The axis is -z with A the rotor and B the
// world, so that the hinge angle (B relative to A about the axis) is the
// rotor's turn about +z.
struct Rotor {
  BodyId body = 0;
  JointId joint = 0;
};

Rotor AddRotor(World& world, double inertia, bool limited = false) {
  Rotor r;
  r.body = testing::AddSphere(world, 0.1, Vec3(0, 0, 1), 0.0);
  world.Find(r.body)->SetMassProperties(1.0, inertia * Mat3::Identity());
  r.joint = testing::AddHinge(world, r.body, kWorldBody, Vec3(0, 0, 1), -Vec3::UnitZ(),
                              limited ? std::optional<std::pair<double, double>>({-3.0, 3.0}) : std::nullopt);
  return r;
}

double Position(const World& world, BodyId body, JointId joint) {
  return JointPosition(*world.FindJoint(joint), *world.Find(body), nullptr);
}
double Rate(const World& world, BodyId body, JointId joint) {
  return JointVelocity(*world.FindJoint(joint), *world.Find(body), nullptr);
}
double Effort(const World& world, JointId joint) { return world.FindJoint(joint)->effort; }

void SetActuator(World& world, JointId joint, const JointActuator& a) {
  const Status st = world.SetJointActuator(joint, a);
  ASSERT_TRUE(st.ok()) << st.message();
}

class ActuatorTest : public ::testing::TestWithParam<MethodConfig> {
 protected:
  bool Refused(const testing::MethodSim& sim) {
    return testing::RefusedByContract(GetParam(), sim.world, testing::ContractOf(GetParam()).joints, "joints");
  }
};

// Verifies the position drive's step response against I th'' = kp (th* -
// th) - kd th': overshoot exp(-zeta pi / sqrt(1 - zeta^2)) and the 2%
// settling time of th*(1 - e^(-zeta w t) (cos w_d t + zeta / sqrt(1 -
// zeta^2) sin w_d t)), each within 2%, for inertias 0.1-10 kg m^2. The
// implicit spring adds a damping ratio w h / 2 (joint_actuator.h), which
// moves the overshoot by pi (w h / 2) / (1 - zeta^2)^1.5 relative: the step
// h = 0.004 / w keeps that below 0.7% at zeta 0.2.
TEST_P(ActuatorTest, PositionDriveFollowsTheMassSpringDamper) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  struct Case {
    double inertia, w, zeta;
  };
  for (const Case& c : {Case{0.1, 6.0, 0.3}, Case{1.0, 4.0, 0.5}, Case{10.0, 8.0, 0.2}}) {
    testing::MethodSim sim(config.method, config.params);
    sim.world.dt = 0.004 / c.w;
    const Rotor r = AddRotor(sim.world, c.inertia);
    if (Refused(sim)) return;
    JointActuator a;
    a.target_position = 0.5;
    a.kp = c.inertia * c.w * c.w;
    a.kd = 2.0 * c.zeta * c.inertia * c.w;
    SetActuator(sim.world, r.joint, a);
    const double zs = std::sqrt(1.0 - c.zeta * c.zeta);
    const double wd = c.w * zs;
    auto analytic = [&](double t) {
      return 0.5 * (1.0 - std::exp(-c.zeta * c.w * t) * (std::cos(wd * t) + c.zeta / zs * std::sin(wd * t)));
    };
    const double horizon = 6.0 / (c.zeta * c.w);
    double peak = 0.0, settle = 0.0, settle_analytic = 0.0;
    while (sim.world.time < horizon) {
      sim.Step();
      const double t = sim.world.time, q = Position(sim.world, r.body, r.joint);
      peak = std::max(peak, q);
      if (std::abs(q - 0.5) > 0.02 * 0.5) settle = t;
      if (std::abs(analytic(t) - 0.5) > 0.02 * 0.5) settle_analytic = t;
    }
    const double overshoot = peak / 0.5 - 1.0, overshoot_analytic = std::exp(-c.zeta * M_PI / zs);
    char id[96];
    std::snprintf(id, sizeof id, "step I=%g w=%g zeta=%g", c.inertia, c.w, c.zeta);
    std::printf("%-10s %-28s overshoot %.4f (analytic %.4f), settling %.3f s (analytic %.3f)\n",
                config.label.c_str(), id, overshoot, overshoot_analytic, settle, settle_analytic);
    checks.Expect(std::string(id) + " overshoot", overshoot / overshoot_analytic, 1.0, 0.02);
    checks.Expect(std::string(id) + " settling", settle / settle_analytic, 1.0, 0.02);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a pendulum (a bob of mass m at l = 0.5 m on a horizontal
// hinge) held by a position drive towards q* rests where kp (q* - q) =
// m g l sin q, the static error of a spring against gravity, and reports
// that effort, for masses 0.1-10 kg.
TEST_P(ActuatorTest, PendulumHeldAgainstGravityHasTheStaticError) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  constexpr double kArm = 0.5, kTarget = 0.5;
  for (const double mass : {0.1, 1.0, 10.0}) {
    testing::MethodSim sim(config.method, config.params);
    const BodyId bob = testing::AddSphere(sim.world, 0.05, Vec3(0, 0, 1.0 - kArm), 0.0);
    sim.world.Find(bob)->SetMass(mass);
    const JointId joint = testing::AddHinge(sim.world, bob, kWorldBody, Vec3(0, 0, 1), -Vec3::UnitY());
    if (Refused(sim)) return;
    const double inertia = mass * (kArm * kArm + 0.4 * 0.05 * 0.05);
    JointActuator a;
    a.target_position = kTarget;
    a.kp = 50.0 * mass;
    a.kd = 2.0 * std::sqrt(a.kp * inertia);  // critical
    SetActuator(sim.world, joint, a);
    while (sim.world.time < 3.0) sim.Step();
    // Newton on kp (q* - q) = m g l sin q
    double q = kTarget;
    for (int i = 0; i < 50; ++i) {
      q -= (a.kp * (kTarget - q) - mass * testing::kG * kArm * std::sin(q)) /
           (-a.kp - mass * testing::kG * kArm * std::cos(q));
    }
    const double measured = Position(sim.world, bob, joint);
    const double effort = mass * testing::kG * kArm * std::sin(q);
    char id[64];
    std::snprintf(id, sizeof id, "hold m=%g", mass);
    std::printf("%-10s %-12s q %.6f (analytic %.6f), effort %.5f N m (analytic %.5f)\n", config.label.c_str(), id,
                measured, q, Effort(sim.world, joint), effort);
    checks.Expect(std::string(id) + " angle", measured, q, 1e-4);
    checks.Expect(std::string(id) + " effort", Effort(sim.world, joint) / effort, 1.0, 1e-3);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a drive far from its target, capped at effort_limit,
// reports exactly that effort every step and turns the rotor as a constant
// torque of that size does: q = E t^2 / (2 I) (within 2 h / t, the
// integrator's lead or lag of a step), for inertias 0.1-10 kg m^2.
TEST_P(ActuatorTest, EffortLimitCapsTheDriveExactly) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double inertia : {0.1, 1.0, 10.0}) {
    testing::MethodSim sim(config.method, config.params);
    const Rotor r = AddRotor(sim.world, inertia);
    if (Refused(sim)) return;
    JointActuator a;
    a.target_position = 3.0;
    a.kp = 1000.0 * inertia;
    a.kd = 10.0 * inertia;
    a.effort_limit = 2.0 * inertia;
    SetActuator(sim.world, r.joint, a);
    double worst_effort = 0.0;
    while (sim.world.time < 0.5) {
      sim.Step();
      worst_effort = std::max(worst_effort, std::abs(Effort(sim.world, r.joint) - a.effort_limit));
    }
    const double t = sim.world.time, h = sim.world.dt;
    const double free = a.effort_limit / inertia * t * t / 2.0;
    char id[64];
    std::snprintf(id, sizeof id, "saturated I=%g", inertia);
    std::printf("%-10s %-16s q %.6f (constant torque %.6f), worst |effort - limit| %.2e\n", config.label.c_str(), id,
                Position(sim.world, r.body, r.joint), free, worst_effort);
    checks.Expect(std::string(id) + " effort", worst_effort / a.effort_limit, 0.0, 1e-9);
    // where in the step a method applies the force (before or after the
    // positions move, at a step or a sub-step) moves q by up to a t h
    checks.Expect(std::string(id) + " motion", Position(sim.world, r.body, r.joint) / free, 1.0, 2.0 * h / t);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that kp = 1e6 N m/rad on a 1 kg link (a pendulum of 0.5 m) at
// dt = 1/240 s settles at its target and never blows up: the implicit
// spring over a step is a damper of kp h (joint_actuator.h).
TEST_P(ActuatorTest, VeryStiffDriveSettles) {
  const MethodConfig& config = GetParam();
  testing::MethodSim sim(config.method, config.params);
  sim.world.dt = 1.0 / 240.0;
  const BodyId bob = testing::AddSphere(sim.world, 0.05, Vec3(0, 0, 0.5), 0.0);
  sim.world.Find(bob)->SetMass(1.0);
  const JointId joint = testing::AddHinge(sim.world, bob, kWorldBody, Vec3(0, 0, 1), -Vec3::UnitY());
  if (Refused(sim)) return;
  JointActuator a;
  a.target_position = 0.3;
  a.kp = 1e6;
  SetActuator(sim.world, joint, a);
  double fastest = 0.0;
  while (sim.world.time < 2.0) {
    sim.Step();
    const double rate = Rate(sim.world, bob, joint);
    ASSERT_TRUE(std::isfinite(rate)) << config.label;
    fastest = std::max(fastest, std::abs(rate));
  }
  const double q = Position(sim.world, bob, joint);
  std::printf("%-10s kp 1e6: q %.7f (target 0.3, static error %.2e), fastest %.3f rad/s\n", config.label.c_str(), q,
              testing::kG * 0.5 * std::sin(0.3) / 1e6, fastest);
  EXPECT_NEAR(q, 0.3, 1e-4) << config.label;
  // never faster than reaching the target in one step (and gravity's g h / l)
  EXPECT_LT(fastest, 0.3 * 240.0 + 1.0) << config.label;
  EXPECT_LT(std::abs(Rate(sim.world, bob, joint)), 1e-4) << config.label;
}

// Verifies velocity control (kp = 0): the rotor reaches target_velocity
// (time constant I / kd), and the velocity limit clamps the target.
TEST_P(ActuatorTest, VelocityDriveReachesItsRateWithinTheLimit) {
  const MethodConfig& config = GetParam();
  for (const double limit : {std::numeric_limits<double>::infinity(), 1.5}) {
    testing::MethodSim sim(config.method, config.params);
    const Rotor r = AddRotor(sim.world, 1.0);
    if (Refused(sim)) return;
    JointActuator a;
    a.target_velocity = 2.0;
    a.kd = 10.0;
    a.velocity_limit = limit;
    SetActuator(sim.world, r.joint, a);
    while (sim.world.time < 2.0) sim.Step();
    const double expected = std::min(2.0, limit);
    std::printf("%-10s velocity limit %g: rate %.8f (target %g), effort %.2e\n", config.label.c_str(), limit,
                Rate(sim.world, r.body, r.joint), expected, Effort(sim.world, r.joint));
    EXPECT_NEAR(Rate(sim.world, r.body, r.joint), expected, 1e-6) << config.label;
    EXPECT_NEAR(Effort(sim.world, r.joint), 0.0, 1e-4) << config.label;
  }
}

// Verifies torque control (kp = kd = 0): I alpha = tau, and the effort
// limit clamps the torque, for inertias 0.1-10 kg m^2.
TEST_P(ActuatorTest, TorqueControlGivesIAlphaEqualsTau) {
  const MethodConfig& config = GetParam();
  for (const double inertia : {0.1, 1.0, 10.0}) {
    for (const double limit : {std::numeric_limits<double>::infinity(), 2.0}) {
      testing::MethodSim sim(config.method, config.params);
      const Rotor r = AddRotor(sim.world, inertia);
      if (Refused(sim)) return;
      JointActuator a;
      a.torque = 3.0;
      a.effort_limit = limit;
      SetActuator(sim.world, r.joint, a);
      while (sim.world.time < 1.0 - 1e-9) sim.Step();
      const double tau = std::min(3.0, limit);
      const double rate = Rate(sim.world, r.body, r.joint);
      EXPECT_NEAR(rate / (tau / inertia * sim.world.time), 1.0, 1e-6) << config.label << " I=" << inertia;
      EXPECT_EQ(Effort(sim.world, r.joint), tau) << config.label;
    }
  }
}

// Verifies that a vertical slider holding a body of mass m against gravity
// with a position drive rests at kp (s* - s) = m g and reports the effort
// m g, for masses 0.1-10 kg. The axis is -z with A the body, so the slide
// s = -z . (p_world - p_A) rises with the body and a positive effort lifts.
TEST_P(ActuatorTest, SliderHoldsItsWeight) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  for (const double mass : {0.1, 1.0, 10.0}) {
    testing::MethodSim sim(config.method, config.params);
    const BodyId body = testing::AddBox(sim.world, Vec3(0.05, 0.05, 0.05), Vec3(0, 0, 1), 0.0, 0.5);
    sim.world.Find(body)->SetMass(mass);
    JointSettings s;
    s.kind = JointKind::kPrismatic;
    s.body_a = body;
    s.anchor = Vec3(0, 0, 1);
    s.axis = -Vec3::UnitZ();
    const JointId joint = testing::AddJoint(sim.world, s);
    if (Refused(sim)) return;
    JointActuator a;
    a.target_position = 0.1;
    a.kp = 1000.0 * mass;
    a.kd = 2.0 * std::sqrt(a.kp * mass);
    SetActuator(sim.world, joint, a);
    while (sim.world.time < 2.0) sim.Step();
    const double weight = mass * testing::kG;
    char id[64];
    std::snprintf(id, sizeof id, "slider m=%g", mass);
    std::printf("%-10s %-12s slide %.6f m (analytic %.6f), effort %.6f N (m g %.6f)\n", config.label.c_str(), id,
                Position(sim.world, body, joint), 0.1 - weight / a.kp, Effort(sim.world, joint), weight);
    checks.Expect(std::string(id) + " effort", Effort(sim.world, joint) / weight, 1.0, 1e-4);
    checks.Expect(std::string(id) + " slide", Position(sim.world, body, joint), 0.1 - weight / a.kp, 1e-5);
  }
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a continuous hinge drives the error the short way round
// (target 2 pi - 0.5 from 0: -0.5, never through +pi), and a hinge with
// limits the plain difference (target 2.5 from 0: +2.5).
TEST_P(ActuatorTest, ContinuousHingeWrapsTheError) {
  const MethodConfig& config = GetParam();
  for (const bool limited : {false, true}) {
    testing::MethodSim sim(config.method, config.params);
    const Rotor r = AddRotor(sim.world, 1.0, limited);
    if (Refused(sim)) return;
    JointActuator a;
    a.target_position = limited ? 2.5 : 2.0 * M_PI - 0.5;
    a.kp = 40.0;
    a.kd = 2.0 * std::sqrt(40.0);
    SetActuator(sim.world, r.joint, a);
    double lowest = 0.0, highest = 0.0;
    while (sim.world.time < 3.0) {
      sim.Step();
      lowest = std::min(lowest, Position(sim.world, r.body, r.joint));
      highest = std::max(highest, Position(sim.world, r.body, r.joint));
    }
    const double expected = limited ? 2.5 : -0.5;
    EXPECT_NEAR(Position(sim.world, r.body, r.joint), expected, 1e-4) << config.label << " limited " << limited;
    if (limited) {
      EXPECT_GT(lowest, -1e-9) << config.label;
    } else {
      EXPECT_LT(highest, 1e-9) << config.label;
    }
  }
}

// A two-finger gripper: a palm on a vertical slider to the world (the
// arm), two fingers on sliders across the palm, every joint a position
// drive. The fingers close on a 10 cm box resting on the table, squeezing
// with their effort limit, the palm lifts it 10 cm along a ramped target
// and holds it: the box rises with the palm and slips no more than 2 mm
// relative to it over 2 s of holding.
struct Gripper {
  BodyId palm = 0, box = 0;
  JointId lift = 0, left = 0, right = 0;
};

constexpr double kSqueeze = 15.0;  // N, each finger's effort limit

Gripper AddGripper(World& world) {
  Gripper g;
  testing::AddGround(world, 0.0, 1.0);
  g.box = testing::AddBox(world, Vec3(0.05, 0.05, 0.05), Vec3(0, 0, 0.05), 0.0, 1.0);
  world.Find(g.box)->SetMass(0.5);
  g.palm = testing::AddBox(world, Vec3(0.12, 0.04, 0.02), Vec3(0, 0, 0.15), 0.0, 1.0);
  world.Find(g.palm)->SetMass(1.0);
  JointSettings lift;
  lift.kind = JointKind::kPrismatic;
  lift.body_a = g.palm;
  lift.anchor = Vec3(0, 0, 0.15);
  lift.axis = -Vec3::UnitZ();  // the slide rises with the palm
  g.lift = testing::AddJoint(world, lift);
  for (const double side : {-1.0, 1.0}) {
    const Vec3 at(side * 0.07, 0, 0.08);
    const BodyId finger = testing::AddBox(world, Vec3(0.01, 0.03, 0.05), at, 0.0, 1.0);
    world.Find(finger)->SetMass(0.1);
    JointSettings s;
    s.kind = JointKind::kPrismatic;
    s.body_a = g.palm;
    s.body_b = finger;
    s.anchor = at;
    s.axis = Vec3(-side, 0, 0);  // the slide closes the finger
    (side < 0 ? g.left : g.right) = testing::AddJoint(world, s);
  }
  return g;
}

TEST_P(ActuatorTest, GripperLiftsABoxWithoutSlipping) {
  const MethodConfig& config = GetParam();
  testing::MechanicsChecks checks(config.label);
  testing::MethodSim sim(config.method, config.params);
  sim.world.dt = 1.0 / 240.0;
  const Gripper g = AddGripper(sim.world);
  if (Refused(sim)) return;
  JointActuator finger;
  finger.target_position = 0.04;  // 2 cm into the box: the drive saturates at kSqueeze
  finger.kp = 2000.0;
  finger.kd = 20.0;
  finger.effort_limit = kSqueeze;
  SetActuator(sim.world, g.left, finger);
  SetActuator(sim.world, g.right, finger);
  JointActuator arm;
  arm.kp = 2e4;
  arm.kd = 2.0 * std::sqrt(arm.kp * 1.7);
  arm.torque = 1.7 * testing::kG;  // feed-forward: the palm, fingers and box
  SetActuator(sim.world, g.lift, arm);
  const double z0 = sim.world.Find(g.box)->x.z();
  double relative0 = 0.0, slip = 0.0, lifted = 0.0;
  while (sim.world.time < 3.5) {
    const double t = sim.world.time;
    arm.target_position = std::clamp(t - 0.5, 0.0, 1.0) * 0.1;  // close, lift over 1 s, hold
    SetActuator(sim.world, g.lift, arm);
    sim.Step();
    const double relative = sim.world.Find(g.box)->x.z() - sim.world.Find(g.palm)->x.z();
    if (t < 1.5) relative0 = relative;
    slip = std::max(slip, std::abs(relative - relative0));
    lifted = sim.world.Find(g.box)->x.z() - z0;
  }
  std::printf("%-10s gripper: box lifted %.5f m, slip %.3e m in 2 s of holding, finger effort %.3f N\n",
              config.label.c_str(), lifted, slip, Effort(sim.world, g.left));
  checks.Expect("gripper lift", lifted, 0.1, 0.005);
  checks.Expect("gripper slip", slip, 0.0, 0.002);
  SKIP_KNOWN_MISSES(checks);
}

// Verifies that a bad actuator is refused with the field named and nothing
// changes: negative or non-finite gains, a non-finite torque or target,
// limits <= 0 or NaN, an unknown joint, a joint without a coordinate.
TEST(ActuatorRefusalTest, BadValuesAreRefusedAndNothingChanges) {
  World world;
  const Rotor r = AddRotor(world, 1.0);
  const BodyId other = testing::AddSphere(world, 0.1, Vec3(1, 0, 1), 0.0);
  const JointId ball = testing::AddJoint(world, JointKind::kBall, other, kWorldBody, Vec3(1, 0, 1.2));
  JointActuator good;
  good.kp = 5.0;
  good.target_position = 0.2;
  ASSERT_TRUE(world.SetJointActuator(r.joint, good).ok());
  const uint64_t hash = HashWorldState(world);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Bad {
    const char* field;
    JointActuator a;
  };
  std::vector<Bad> bads;
  auto add = [&](const char* field, auto set) {
    JointActuator a = good;
    set(a);
    bads.push_back({field, a});
  };
  add("kp", [&](JointActuator& a) { a.kp = -1.0; });
  add("kp", [&](JointActuator& a) { a.kp = inf; });
  add("kd", [&](JointActuator& a) { a.kd = nan; });
  add("torque", [&](JointActuator& a) { a.torque = inf; });
  add("target_position", [&](JointActuator& a) { a.target_position = nan; });
  add("target_velocity", [&](JointActuator& a) { a.target_velocity = -inf; });
  add("effort_limit", [&](JointActuator& a) { a.effort_limit = 0.0; });
  add("effort_limit", [&](JointActuator& a) { a.effort_limit = nan; });
  add("velocity_limit", [&](JointActuator& a) { a.velocity_limit = -1.0; });
  for (const Bad& b : bads) {
    const Status st = world.SetJointActuator(r.joint, b.a);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << b.field;
    EXPECT_NE(st.message().find(b.field), std::string::npos) << st.message();
  }
  EXPECT_EQ(world.SetJointActuator(99, good).code(), StatusCode::kNotFound);
  EXPECT_EQ(world.SetJointActuator(ball, good).code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(world.FindJoint(r.joint)->actuator.kp, 5.0);
  EXPECT_EQ(world.FindJoint(ball)->actuator.kp, 0.0);
  EXPECT_EQ(HashWorldState(world), hash);
}

// Verifies that the actuator enters the world hash only when it acts: a
// world whose joints carry only limits (as a model's) hashes as without.
TEST(ActuatorRefusalTest, HashCountsOnlyActuatedJoints) {
  World world;
  const Rotor r = AddRotor(world, 1.0);
  const uint64_t bare = HashWorldState(world);
  JointActuator limits;
  limits.effort_limit = 5.0;
  ASSERT_TRUE(world.SetJointActuator(r.joint, limits).ok());
  EXPECT_EQ(HashWorldState(world), bare);
  JointActuator driven = limits;
  driven.kd = 1.0;
  ASSERT_TRUE(world.SetJointActuator(r.joint, driven).ok());
  const uint64_t with_kd = HashWorldState(world);
  EXPECT_NE(with_kd, bare);
  driven.target_velocity = 1.0;
  ASSERT_TRUE(world.SetJointActuator(r.joint, driven).ok());
  EXPECT_NE(HashWorldState(world), with_kd);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, ActuatorTest, ::testing::ValuesIn(testing::JointedWorldConfigs()),
                         testing::ConfigName);

}  // namespace
}  // namespace contactsim
