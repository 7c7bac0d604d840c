// Tests of the lcp contact method against analytic results, for both solvers.
#include "service/contact/lcp/lcp_method.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kG = 9.81;  // m/s^2

using testing::AddBox;
using testing::AddGround;
using testing::AddSphere;

using testing::MechanicalEnergy;
// The shared MethodSim with lcp and a solver.
struct Sim : testing::MethodSim {
  explicit Sim(const std::string& solver) : MethodSim("lcp", {{"solver", solver}}) {}
  LcpMethod& lcp() { return static_cast<LcpMethod&>(*method); }
};

class LcpSolverTest : public ::testing::TestWithParam<const char*> {};

// Verifies that a sphere dropped from h = 1 m rebounds to e^2 h within 2%
// for e = 0.5 (Newton's law at the velocity level, v+ = -e v-).
TEST_P(LcpSolverTest, SphereReboundsToESquaredTimesDropHeight) {
  const double e = 0.5, r = 0.1, h = 1.0;
  Sim sim(GetParam());
  AddGround(sim.world, e, 0.5);
  const BodyId ball = AddSphere(sim.world, r, Vec3(0, 0, h + r), e);
  bool bounced = false;
  double apex = -1e9, last_vz = 0.0;
  for (int i = 0; i < 2000; ++i) {
    sim.Step();
    const RigidBody& b = *sim.world.Find(ball);
    const double vz = b.LinearVelocity().z();
    if (!bounced && last_vz < 0.0 && vz > 0.0) bounced = true;
    if (bounced) {
      apex = std::max(apex, b.x.z() - r);
      if (vz < 0.0) break;
    }
    last_vz = vz;
  }
  EXPECT_NEAR(apex, e * e * h, 0.02 * e * e * h);
  std::printf("%s: rebound apex %.5f m, analytic %.5f m (%.2f%%)\n", GetParam(), apex, e * e * h,
              100.0 * (apex - e * e * h) / (e * e * h));
}

// Verifies that a box sliding at v0 = 3 m/s with mu = 0.4 stops after
// v0^2 / (2 mu g) within 3% (Coulomb friction, deceleration mu g).
TEST_P(LcpSolverTest, SlidingBoxStopsAtAnalyticDistance) {
  const double mu = 0.4, v0 = 3.0, half = 0.1;
  Sim sim(GetParam());
  AddGround(sim.world, 0.0, mu);
  const BodyId box = AddBox(sim.world, half, Vec3(0, 0, half), 0.0, mu, Vec3(v0, 0, 0));
  for (int i = 0; i < 480; ++i) sim.Step();  // 2 s; it stops after 0.76 s
  const double expected = v0 * v0 / (2.0 * mu * kG);
  const RigidBody& b = *sim.world.Find(box);
  EXPECT_NEAR(b.x.x(), expected, 0.03 * expected);
  EXPECT_LT(b.LinearVelocity().norm(), 1e-3);
  std::printf("%s: stopped after %.4f m, analytic %.4f m (%.2f%%)\n", GetParam(), b.x.x(), expected,
              100.0 * (b.x.x() - expected) / expected);
}

// Verifies that a box resting on the plane has zero acceleration (its
// velocity stays zero step after step) and that the normal impulses of a
// step sum to its weight times the step, m g h.
TEST_P(LcpSolverTest, RestingBoxHasZeroAccelerationAndCarriesItsWeight) {
  const double half = 0.25;
  Sim sim(GetParam());
  AddGround(sim.world, 0.5, 0.5);
  const BodyId box = AddBox(sim.world, half, Vec3(0, 0, half), 0.5, 0.5);
  for (int i = 0; i < 240; ++i) sim.Step();
  const RigidBody& b = *sim.world.Find(box);
  for (int i = 0; i < 10; ++i) {
    const Vec3 v0 = b.LinearVelocity(), w0 = b.AngularVelocity();
    const StepStats stats = sim.Step();
    EXPECT_EQ(stats.contacts, 4);
    // acceleration (v1 - v0) / h; PGS stops at a 1e-6 m/s residual
    EXPECT_LT((b.LinearVelocity() - v0).norm() / sim.world.dt, 1e-3);
    EXPECT_LT((b.AngularVelocity() - w0).norm() / sim.world.dt, 1e-3);
    double sum = 0.0;
    for (const Contact& c : sim.contacts) sum += c.normal_value;
    EXPECT_NEAR(sum, b.mass * kG * sim.world.dt, 1e-6 * b.mass * kG * sim.world.dt);
  }
  EXPECT_NEAR(b.x.z(), half, 1e-3);  // within the slop
  EXPECT_LT(b.LinearVelocity().norm(), 1e-5);
}

// Verifies a live switch impulse -> lcp -> penalty -> lcp: no body jumps
// by more than g h^2 beyond v h (or the new method's rest depth) and the
// energy does not rise (lcp and penalty add none; impulse may lift a box
// sunk deeper than its slop: m g d < 0.08 J for the 8 kg box).
TEST_P(LcpSolverTest, LiveSwitchKeepsPositionsAndEnergy) {
  const double kMaxJump = 1e-3;       // m
  const double kMaxEnergyRise = 0.1;  // J
  Sim sim(GetParam());
  ASSERT_TRUE(CreateContactMethod("impulse", &sim.method).ok());
  AddGround(sim.world, 0.5, 0.5);
  const BodyId ball = AddSphere(sim.world, 0.1, Vec3(0, 0, 3.1), 0.5);
  const BodyId box = AddBox(sim.world, 0.1, Vec3(1, 0, 0.1), 0.5, 0.5);
  for (int i = 0; i < 48; ++i) sim.Step();
  for (const char* next : {"lcp", "penalty", "lcp", "impulse"}) {
    ASSERT_TRUE(CreateContactMethod(next, &sim.method).ok());
    if (std::string(next) == "lcp") {
      ASSERT_TRUE(sim.method->SetParams({{"solver", GetParam()}}).ok());
    }
    const double e0 = MechanicalEnergy(sim.world);
    double rise = 0.0;
    for (int i = 0; i < 24; ++i) {
      std::vector<Vec3> x0, v0;
      for (const RigidBody& b : sim.world.bodies()) x0.push_back(b.x), v0.push_back(b.LinearVelocity());
      sim.Step();
      for (BodyId id : {ball, box}) {
        const int k = sim.world.IndexOf(id);
        const Vec3 step = sim.world.bodies()[k].x - x0[k];
        EXPECT_LT((step - v0[k] * sim.world.dt).norm(), kMaxJump) << next << " step " << i << " body " << id;
      }
      rise = std::max(rise, MechanicalEnergy(sim.world) - e0);
    }
    EXPECT_LT(rise, kMaxEnergyRise) << "after switching to " << next;
  }
  EXPECT_NEAR(sim.world.Find(box)->x.z(), 0.1, 1e-3);
}

// Verifies determinism: the same scene and steps give bit-identical worlds.
TEST_P(LcpSolverTest, IsDeterministic) {
  auto run = [] {
    Sim sim(GetParam());
    AddGround(sim.world, 0.3, 0.5);
    for (int i = 0; i < 4; ++i) AddBox(sim.world, 0.1, Vec3(0.03 * i, 0, 0.1 + 0.21 * i), 0.3, 0.5);
    AddSphere(sim.world, 0.1, Vec3(0.5, 0, 0.5), 0.3);
    for (int i = 0; i < 200; ++i) sim.Step();
    return HashWorldState(sim.world);
  };
  EXPECT_EQ(run(), run());
}

INSTANTIATE_TEST_SUITE_P(Solvers, LcpSolverTest, ::testing::Values("pgs", "lemke"));

// Verifies that warm starting pays: on a resting box the warm-started PGS
// stops at its floor of two sweeps a step once settled (pgs.h, "Warm-started
// solves") with its last sweep moving nothing, where a cold start's last
// sweep still moves the rows, and the cache holds one entry per
// contact feature (four corners) and is dropped by ResetCaches.
TEST(LcpMethod, WarmStartByFeatureIdConvergesInTheFewestSweeps) {
  Sim sim("pgs");
  AddGround(sim.world, 0.5, 0.5);
  AddBox(sim.world, 0.1, Vec3(0, 0, 0.1), 0.5, 0.5);
  for (int i = 0; i < 120; ++i) sim.Step();
  const StepStats stats = sim.Step();
  EXPECT_EQ(stats.iterations, 2);
  EXPECT_LT(stats.residual, 1e-6);
  EXPECT_EQ(sim.lcp().warm_start().size(), 4u);
  sim.method->ResetCaches();
  EXPECT_EQ(sim.lcp().warm_start().size(), 0u);
  // the cold solve also meets the tolerance in two sweeps here, but its
  // second sweep still moves the rows (3e-18 m/s against 2e-33 warm)
  const StepStats cold = sim.Step();
  EXPECT_EQ(cold.iterations, 2);
  EXPECT_GT(cold.residual, 1e6 * stats.residual);
  EXPECT_GT(cold.residual, 0.0);
}

// Verifies that Lemke's fallback is the pgs solver, warm start included:
// with max_lemke_rows = 0 every step falls back, and a stack of four boxes
// with a pendulum (contact and joint rows) runs bit for bit as under
// solver = pgs at the fallback's tolerance (1e-6 m/s), with every step
// counted as a fallback.
TEST(LcpMethod, LemkeFallsBackToTheWarmStartedPgsSolver) {
  auto run = [](const ParamMap& params, int* fallbacks) {
    testing::MethodSim sim("lcp", params);
    AddGround(sim.world, 0.0, 0.5);
    for (int i = 0; i < 4; ++i) AddBox(sim.world, 0.1, Vec3(0.02 * i, 0, 0.1 + 0.2 * i), 0.0, 0.5);
    JointSettings rod;
    rod.kind = JointKind::kDistance;
    rod.body_a = AddSphere(sim.world, 0.05, Vec3(1.3, 0, 1.0), 0.0);
    rod.anchor = Vec3(1.0, 0, 1.5);
    JointId id = 0;
    EXPECT_TRUE(sim.world.AddJoint(rod, &id).ok());
    for (int i = 0; i < 240; ++i) sim.Step();
    *fallbacks = static_cast<LcpMethod&>(*sim.method).lemke_fallbacks();
    return HashWorldState(sim.world);
  };
  int pgs_fallbacks = -1, lemke_fallbacks = -1;
  const uint64_t pgs = run({{"solver", "pgs"}, {"tolerance", "1e-6"}}, &pgs_fallbacks);
  const uint64_t lemke = run({{"solver", "lemke"}, {"max_lemke_rows", "0"}}, &lemke_fallbacks);
  EXPECT_EQ(lemke, pgs);
  EXPECT_EQ(pgs_fallbacks, 0);
  EXPECT_EQ(lemke_fallbacks, 240);
}

// Verifies that bad parameters are rejected with the name and the value,
// and leave the parameters unchanged.
TEST(LcpMethod, RejectsBadParametersByName) {
  LcpMethod method;
  Status st = method.SetParams({{"solver", "dantzig"}});
  EXPECT_FALSE(st.ok());
  EXPECT_NE(st.message().find("solver"), std::string::npos) << st.message();
  EXPECT_NE(st.message().find("dantzig"), std::string::npos) << st.message();
  st = method.SetParams({{"iterations", "50"}, {"erp", "-1"}});
  EXPECT_NE(st.message().find("erp"), std::string::npos) << st.message();
  EXPECT_EQ(method.params().iterations, LcpParams().iterations);
  EXPECT_TRUE(method.SetParams({{"solver", "lemke"}, {"drift", "baumgarte"}}).ok());
  EXPECT_EQ(method.Params().at("solver"), "lemke");
}

}  // namespace
}  // namespace contactsim
