// Tests of the penalty method against analytic results, its friction, its
// two integrators and a live switch with the impulse method.
#include "service/contact/penalty/penalty_method.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "service/contact/impulse/impulse_method.h"
#include "service/physics/body_settings.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;

using testing::MechanicalEnergy;
struct Sim {
  World world;
  CollisionDetector detector;
  std::unique_ptr<ContactMethod> method = std::make_unique<PenaltyMethod>();
  ContactSet contacts;
  explicit Sim(const ParamMap& params = {}) {
    const Status st = method->SetParams(params);
    EXPECT_TRUE(st.ok()) << st.message();
  }
  StepStats Step() { return method->Step(world, detector, &contacts); }
};

// Highest z of a body's centre after its first contact with the ground.
double FirstReboundApex(Sim& sim, BodyId id, int max_steps) {
  bool bounced = false;
  double apex = -1e9, last_vz = 0.0;
  for (int i = 0; i < max_steps; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(id);
    const double vz = b.LinearVelocity().z();
    if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.x.z());
      if (vz < 0.0) break;
    }
    last_vz = vz;
  }
  return apex;
}

// The two integrators, each with settings where a bounce is resolved:
// sqrt(kp / m) h is 0.04 (explicit, 16 sub-steps) and 0.16 (implicit, 4).
// The implicit step runs as the trapezoidal rule (theta = 0.5): the default
// theta = 1 damps a linear spring numerically by about exp(-pi omega h / 2)
// per bounce, far more than e = 0.9 allows (see the next test).
struct BounceCase {
  const char* name;
  ParamMap params;
};

const BounceCase kBounceCases[] = {
    {"explicit", {{"integrator", "explicit"}, {"kp", "1e5"}, {"substeps", "16"}}},
    {"implicit", {{"integrator", "implicit"}, {"theta", "0.5"}, {"kp", "1e5"}, {"substeps", "4"}}},
};

class PenaltyBounceTest : public ::testing::TestWithParam<std::tuple<double, int>> {};

// Verifies that a sphere dropped from h rebounds to e^2 h within 10% with kd
// derived from e, for both integrators.
TEST_P(PenaltyBounceTest, SphereReboundsToESquaredTimesDropHeight) {
  // 10%: the required bound; the rest is physics of the model (the contact
  // lets go at depth kd v / kp, and gravity acts during the contact: 4.5%
  // low at kp = 1e5 for e = 0.5 in the continuous model) and the step
  const double kTolerance = 0.10;
  const auto [e, which] = GetParam();
  const BounceCase& c = kBounceCases[which];
  ParamMap params = c.params;
  params["restitution"] = std::to_string(e);
  Sim sim(params);
  const double r = 0.1, h = 1.0;
  AddGround(sim.world, e, 0.5);
  const BodyId ball = AddSphere(sim.world, r, Vec3(0, 0, h + r), e);
  const double apex = FirstReboundApex(sim, ball, 2400) - r;
  EXPECT_NEAR(apex, e * e * h, kTolerance * e * e * h) << c.name << ", e = " << e;
  std::printf("%s e = %.1f: rebound apex %.4f m, analytic %.4f m (%+.1f%%)\n", c.name, e, apex, e * e * h,
              100.0 * (apex - e * e * h) / (e * e * h));
}

INSTANTIATE_TEST_SUITE_P(RestitutionAndIntegrator, PenaltyBounceTest,
                         ::testing::Combine(::testing::Values(0.5, 0.9), ::testing::Values(0, 1)));

// Verifies that the implicit step (theta = 1) never bounces higher than the
// analytic height: its numerical damping only removes energy.
TEST(PenaltyMethod, ImplicitStepBouncesNoHigherThanAnalytic) {
  for (double e : {0.5, 0.9}) {
    Sim sim({{"restitution", std::to_string(e)}, {"integrator", "implicit"}});
    AddGround(sim.world, e, 0.5);
    const BodyId ball = AddSphere(sim.world, 0.1, Vec3(0, 0, 1.1), e);
    const double apex = FirstReboundApex(sim, ball, 2400) - 0.1;
    EXPECT_GT(apex, 0.0);
    EXPECT_LT(apex, e * e);
    std::printf("implicit theta = 1, e = %.1f: rebound apex %.4f m, analytic %.4f m\n", e, apex, e * e);
  }
}

// Verifies the Hunt-Crossley option: a sphere with e = 0.9 rebounds to
// e^2 h within 10% (alpha from e after Flores et al. 2011).
TEST(PenaltyMethod, HuntCrossleySphereReboundsToESquaredTimesDropHeight) {
  const double kTolerance = 0.10;  // as for the linear law
  const double e = 0.9;
  for (const char* integrator : {"explicit", "implicit"}) {
    Sim sim({{"model", "hunt_crossley"}, {"kp", "1e6"}, {"integrator", integrator}, {"theta", "0.5"},
             {"substeps", "4"}, {"restitution", "0.9"}});
    AddGround(sim.world, e, 0.5);
    const BodyId ball = AddSphere(sim.world, 0.1, Vec3(0, 0, 1.1), e);
    const double apex = FirstReboundApex(sim, ball, 2400) - 0.1;
    EXPECT_NEAR(apex, e * e, kTolerance * e * e) << integrator;
    std::printf("hunt_crossley %s e = 0.9: rebound apex %.4f m, analytic %.4f m (%+.1f%%)\n", integrator, apex, e * e,
                100.0 * (apex - e * e) / (e * e));
  }
}

class PenaltyIntegratorTest : public ::testing::TestWithParam<const char*> {};

// The explicit step with the stiffnesses it is stable with for a 0.2 m box
// (the defaults, 1e6 N/m, are for the implicit step); the implicit step
// with its defaults.
ParamMap FrictionParams(const std::string& integrator) {
  if (integrator == "explicit") return {{"integrator", integrator}, {"kp", "1e5"}, {"friction_stiffness", "1e5"}};
  return {{"integrator", integrator}};
}

double FrictionStiffness(const ParamMap& params) {
  const auto it = params.find("friction_stiffness");
  return it == params.end() ? PenaltyParams().friction_stiffness : std::stod(it->second);
}

// Verifies that a box sliding at v0 with friction mu stops after
// v0^2 / (2 mu g) within 3% (the anchor slides at |f_t| = mu lambda).
TEST_P(PenaltyIntegratorTest, SlidingBoxStopsAtAnalyticDistance) {
  const double kTolerance = 0.03;  // the required bound
  const double mu = 0.4, v0 = 3.0, half = 0.1;
  Sim sim(FrictionParams(GetParam()));
  AddGround(sim.world, 0.0, mu);
  const BodyId box = AddBox(sim.world, half, Vec3(0, 0, half), 0.0, mu, Vec3(v0, 0, 0));
  for (int i = 0; i < 2400; ++i) sim.Step();
  const double expected = v0 * v0 / (2.0 * mu * kG);
  const RigidBody& b = *sim.world.Find(box);
  EXPECT_NEAR(b.x.x(), expected, kTolerance * expected);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-3);
  std::printf("%s: stopped after %.4f m, analytic %.4f m (%+.2f%%)\n", GetParam(), b.x.x(), expected,
              100.0 * (b.x.x() - expected) / expected);
}

// Verifies static and dynamic friction: under a sideways force of half of
// mu m g the box holds (the tangential springs stretch by about F / kt and
// stop; no creep), and under 1.5 mu m g it slides with a = (F - mu m g) / m.
TEST_P(PenaltyIntegratorTest, BoxHoldsBelowCoulombLimitAndSlidesAbove) {
  const double mu = 0.5, half = 0.1;
  const ParamMap params = FrictionParams(GetParam());
  const double kt = FrictionStiffness(params);
  for (double fraction : {0.5, 1.5}) {
    Sim sim(params);
    AddGround(sim.world, 0.0, mu);
    const BodyId box = AddBox(sim.world, half, Vec3(0, 0, half), 0.0, mu);
    for (int i = 0; i < 240; ++i) sim.Step();  // settle for 1 s
    const Vec3 x0 = sim.world.Find(box)->x;
    const double force = fraction * mu * sim.world.Find(box)->mass * kG;
    sim.world.AddWrench({box, Vec3(force, 0, 0), Vec3::Zero(), 2.0});
    for (int i = 0; i < 240; ++i) sim.Step();
    const double x1 = sim.world.Find(box)->x.x() - x0.x();
    for (int i = 0; i < 240; ++i) sim.Step();
    const double x2 = sim.world.Find(box)->x.x() - x0.x();
    if (fraction < 1.0) {
      // the springs carry F with a stretch of F / kt; the load shifts to the
      // front corners as the force tips the box, so allow three times that
      EXPECT_LT(std::abs(x2), 3.0 * force / kt) << GetParam();
      // no creep between 1 s and 2 s of load (measured: below 1e-6 m)
      EXPECT_NEAR(x2, x1, 1e-5) << GetParam();
      std::printf("%s: held %.1f N with %.3f mm (F / kt = %.3f mm)\n", GetParam(), force, 1e3 * x2, 1e3 * force / kt);
    } else {
      // 5%: the first steps of the load rock the box onto its front edge
      const double a = (fraction - 1.0) * mu * kG;
      EXPECT_NEAR(x2, 0.5 * a * 4.0, 0.05 * 0.5 * a * 4.0) << GetParam();
      std::printf("%s: slid %.4f m in 2 s, analytic %.4f m\n", GetParam(), x2, 0.5 * a * 4.0);
    }
  }
}

// Verifies that a box resting on the plane settles at the depth that
// balances its weight, kp d = m g (linear) and kp d^n = m g (Hunt-Crossley),
// within 5%. The explicit step's placed start (preload) begins with the
// springs compressed by the weight's share and gives that back at
// preload_drain_speed (1 mm/s), so the 10 s cover the Hunt-Crossley depth
// (8.5 mm).
TEST_P(PenaltyIntegratorTest, RestingBoxSettlesAtWeightBalancingDepth) {
  const double kTolerance = 0.05;  // the required bound; measured to round-off
  const double kp = 1e5, half = 0.1;
  for (const char* model : {"linear", "hunt_crossley"}) {
    Sim sim({{"integrator", GetParam()}, {"model", model}, {"kp", "1e5"}});
    AddGround(sim.world, 0.5, 0.5);
    const BodyId box = AddBox(sim.world, half, Vec3(0, 0, half), 0.5, 0.5);
    for (int i = 0; i < 2400; ++i) sim.Step();
    const RigidBody& b = *sim.world.Find(box);
    const double weight = b.mass * kG;
    const double expected = std::string(model) == "linear" ? weight / kp : std::pow(weight / kp, 1.0 / 1.5);
    EXPECT_NEAR(half - b.x.z(), expected, kTolerance * expected) << model;
  }
}

// Verifies that a contact off the centre of mass makes a torque: one corner
// of a tilted box pressed into the plane changes P by h F and L by
// h (p - x) x F, with F = lambda n at the contact point p.
TEST_P(PenaltyIntegratorTest, OffCentreContactMakesTorque) {
  const double kp = 1e5, depth = 1e-3, half = 0.1;
  // max_omega_h = 2: one explicit sub-step, so that the force is the one at
  // the step's start
  Sim sim({{"integrator", GetParam()},
           {"kp", "1e5"},
           {"restitution", "off"},
           {"kd", "0"},
           {"margin", "0"},
           {"max_omega_h", "2"},
           // the corner starts at depth: a contact, not a placement to push out slowly
           {"overlap_push_speed", "1000"}});
  sim.world.gravity.setZero();
  AddGround(sim.world, 0.5, 0.0);
  const BodyId id = AddBox(sim.world, half, Vec3::Zero(), 0.5, 0.0);
  RigidBody& box = *sim.world.Find(id);
  box.q = Quat(Eigen::AngleAxisd(0.3, Vec3::UnitX()) * Eigen::AngleAxisd(0.4, Vec3::UnitY()));
  // the lowest corner at z = -depth
  Vec3 lowest = Vec3::Constant(1e9);
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner(i & 1 ? half : -half, i & 2 ? half : -half, i & 4 ? half : -half);
    const Vec3 p = box.Rotation() * corner;
    if (p.z() < lowest.z()) lowest = p;
  }
  box.x = Vec3(0, 0, -depth - lowest.z());
  const Vec3 x0 = box.x, P0 = box.P, L0 = box.L;
  const Vec3 point = x0 + lowest + Vec3(0, 0, 0.5 * depth);  // midway between corner and plane
  sim.Step();
  ASSERT_EQ(sim.contacts.size(), 1u);
  const double lambda = sim.contacts[0].normal_value;
  const double h = sim.world.dt;
  const RigidBody& b = *sim.world.Find(id);
  // explicit: lambda = kp d exactly; implicit: kp times the depth at the
  // step's end, a little less as the corner moves out
  if (std::string(GetParam()) == "explicit") {
    EXPECT_NEAR(lambda, kp * depth, 1e-9 * kp * depth);
  }
  EXPECT_GT(lambda, 0.5 * kp * depth);
  const Vec3 F = lambda * Vec3::UnitZ();
  // round-off of one step's sums of O(1) values
  EXPECT_LT((b.P - P0 - h * F).norm(), 1e-12);
  EXPECT_LT((b.L - L0 - h * (point - x0).cross(F)).norm(), 1e-12);
  EXPECT_GT((b.L - L0).norm(), 0.5 * h * lambda * half);  // a real torque, not round-off
}

// Verifies that a stack of five boxes stays standing with bounded energy at
// kp = 1e7 N/m (dt = 1/240 s): on the implicit step, and on the explicit
// step, which takes the sub-steps its stiffest mode needs (it diverged with
// one).
TEST_P(PenaltyIntegratorTest, StiffStackOfFiveBoxes) {
  const double half = 0.1;
  Sim sim({{"integrator", GetParam()}, {"kp", "1e7"}});
  AddGround(sim.world, 0.5, 0.5);
  for (int i = 0; i < 5; ++i) AddBox(sim.world, half, Vec3(0, 0, half * (1 + 2 * i)), 0.5, 0.5);
  const double e0 = MechanicalEnergy(sim.world);
  double worst_rise = 0.0, worst_depth = 0.0;
  bool finite = true;
  for (int i = 0; i < 480 && finite; ++i) {
    worst_depth = std::max(worst_depth, sim.Step().max_penetration);
    for (const RigidBody& b : sim.world.bodies()) finite = finite && b.x.allFinite() && b.P.allFinite();
    worst_rise = std::max(worst_rise, MechanicalEnergy(sim.world) - e0);
  }
  const bool stable = finite && worst_depth < half && worst_rise < 0.01 * e0;
  if (std::string(GetParam()) == "implicit") {
    EXPECT_TRUE(stable);
    EXPECT_LT(worst_depth, 1e-4);  // 5 boxes' weight over kp = 1e7 is 4e-5 m
    EXPECT_LT(worst_rise, 1e-6 * e0);  // energy never rises: only round-off
    // the top sinks by the five contacts' compressions, (1+2+3+4+5) m g / kp
    const double sink = 15.0 * sim.world.bodies().back().mass * kG / 1e7;
    EXPECT_NEAR(sim.world.bodies().back().x.z(), 9.0 * half - sink, 1e-6);
  } else {
    EXPECT_TRUE(stable) << "explicit step unstable at kp = 1e7 (worst depth " << worst_depth << ")";
    EXPECT_LT(worst_depth, 1e-4);
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, PenaltyIntegratorTest, ::testing::Values("explicit", "implicit"));

// Verifies that parameters are validated as a whole: a bad value names the
// parameter and the value, and nothing changes.
TEST(PenaltyMethod, RejectsBadParametersAndKeepsTheOldOnes) {
  PenaltyMethod m;
  const PenaltyParams before = m.params();
  const std::pair<ParamMap, const char*> bad[] = {
      {{{"kp", "-1"}}, "kp"},
      {{{"kd", "abc"}}, "kd"},
      {{{"restitution", "2"}}, "restitution"},
      {{{"restitution", "bouncy"}}, "restitution"},
      {{{"friction_stiffness", "0"}}, "friction_stiffness"},
      {{{"integrator", "rk4"}}, "integrator"},
      {{{"model", "hertz"}}, "model"},
      {{{"margin", "1"}}, "margin"},
      {{{"theta", "0.2"}}, "theta"},
      {{{"kp", "2e5"}, {"substeps", "0"}}, "substeps"},
  };
  for (const auto& [params, name] : bad) {
    const Status st = m.SetParams(params);
    EXPECT_FALSE(st.ok()) << name;
    EXPECT_NE(st.message().find(name), std::string::npos) << st.message();
    EXPECT_NE(st.message().find(params.rbegin()->second), std::string::npos) << st.message();
  }
  EXPECT_EQ(m.params().kp, before.kp);
  const Status st = m.SetParams({{"nosuch", "1"}});
  EXPECT_NE(st.message().find("unknown parameter \"nosuch\""), std::string::npos) << st.message();
  // kd alone means "use kd"; Params() fed back gives the same method
  ASSERT_TRUE(m.SetParams({{"kd", "250"}, {"integrator", "explicit"}}).ok());
  EXPECT_EQ(m.params().restitution, "off");
  EXPECT_EQ(m.params().kd, 250.0);
  PenaltyMethod copy;
  ASSERT_TRUE(copy.SetParams(m.Params()).ok());
  EXPECT_EQ(copy.Params(), m.Params());
  ASSERT_TRUE(m.SetParams({{"restitution", "0.7"}}).ok());
  EXPECT_EQ(m.params().RestitutionValue(), 0.7);
}

// Verifies a live switch at engine level: impulse -> penalty -> impulse on
// the same World, each time while a sphere falls and a box rests. No body
// jumps (a step moves it by v h up to O(g h^2)) and the energy does not rise
// beyond the new method's transient.
TEST(PenaltyMethod, LiveSwitchWithImpulseKeepsPositionsAndEnergy) {
  // A switch step moves a body by v h + O(g h^2) (1.7e-4 m) or, for the
  // resting box, by the new method's rest depth, m g / kp = 0.08 mm
  const double kMaxJump = 1e-3;  // m
  // Energy may rise only by what the new method's transient adds: impulse
  // lifts a box sunk into the plane deeper than its slop (m g d with d <
  // 1 mm: 0.08 J for the 8 kg box), penalty never adds energy
  const double kMaxEnergyRise = 0.1;  // J
  Sim sim;
  sim.method = std::make_unique<ImpulseMethod>();
  AddGround(sim.world, 0.5, 0.5);
  const BodyId ball = AddSphere(sim.world, 0.1, Vec3(0, 0, 3.1), 0.5);
  const BodyId box = AddBox(sim.world, 0.1, Vec3(1, 0, 0.1), 0.5, 0.5);
  for (int i = 0; i < 48; ++i) sim.Step();  // 0.2 s: ball falling, box at rest
  for (const char* next : {"penalty", "impulse", "penalty", "impulse"}) {
    ASSERT_TRUE(CreateContactMethod(next, &sim.method).ok());
    const double e0 = MechanicalEnergy(sim.world);
    double rise = 0.0, jump = 0.0;
    for (int i = 0; i < 24; ++i) {  // 0.1 s with the new method
      std::vector<Vec3> x0, v0;
      for (const RigidBody& b : sim.world.bodies()) x0.push_back(b.x), v0.push_back(b.LinearVelocity());
      sim.Step();
      for (BodyId id : {ball, box}) {
        const int k = sim.world.IndexOf(id);
        const Vec3 step = sim.world.bodies()[k].x - x0[k];
        jump = std::max(jump, (step - v0[k] * sim.world.dt).norm());
        EXPECT_LT((step - v0[k] * sim.world.dt).norm(), kMaxJump) << next << " step " << i << " body " << id;
      }
      rise = std::max(rise, MechanicalEnergy(sim.world) - e0);
    }
    EXPECT_LT(rise, kMaxEnergyRise) << "after switching to " << next;
    EXPECT_GT(sim.world.Find(ball)->x.z(), 0.5) << "the ball is still falling";
    std::printf("switch to %s: largest jump %.2e m, energy rise %.2e J, box z %.6f m\n", next, jump, rise,
                sim.world.Find(box)->x.z());
  }
  EXPECT_NEAR(sim.world.Find(box)->x.z(), 0.1, 1e-3);
}

// Verifies that anchors live per contact feature: a resting box keeps four,
// a lifted box loses them, and ResetCaches drops them.
TEST(PenaltyMethod, AnchorsFollowTheContacts) {
  Sim sim;
  AddGround(sim.world, 0.5, 0.5);
  const BodyId box = AddBox(sim.world, 0.1, Vec3(0, 0, 0.1), 0.5, 0.5);
  for (int i = 0; i < 60; ++i) sim.Step();
  auto& penalty = static_cast<PenaltyMethod&>(*sim.method);
  EXPECT_EQ(penalty.anchors().size(), 4u);
  const RigidBody resting = *sim.world.Find(box);
  sim.world.Find(box)->x.z() += 0.5;
  sim.Step();
  EXPECT_EQ(penalty.anchors().size(), 0u);
  *sim.world.Find(box) = resting;  // back at rest, as it was
  sim.Step();
  EXPECT_EQ(penalty.anchors().size(), 4u);
  penalty.ResetCaches();
  EXPECT_EQ(penalty.anchors().size(), 0u);
}

// Verifies determinism: the same scene and steps give bit-identical worlds.
TEST(PenaltyMethod, IsDeterministic) {
  auto run = [] {
    Sim sim;
    AddGround(sim.world, 0.5, 0.5);
    for (int i = 0; i < 3; ++i) AddBox(sim.world, 0.1, Vec3(0.05 * i, 0, 0.1 + 0.25 * i), 0.5, 0.5);
    AddSphere(sim.world, 0.1, Vec3(0.3, 0, 0.5), 0.5);
    for (int i = 0; i < 480; ++i) sim.Step();
    return HashWorldState(sim.world);
  };
  EXPECT_EQ(run(), run());
}

}  // namespace
}  // namespace contactsim
