// Tests of the lcp method's two impact laws across simultaneous contacts
// (lcp_impacts.h, the `impacts` parameter) on a sphere struck into touching
// spheres of its mass, without gravity or friction, with both solvers.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "tests/contact/line_impacts.h"
#include "tests/contact/method_sim.h"
#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace {

constexpr double kRadius = 0.05;  // m
constexpr double kV0 = 2.0;       // m/s

// Velocities along the line (m/s) 0.05 s after a sphere struck at kV0 into
// `row` touching spheres, all of `mass` and restitution e. pgs sweeps to
// 1e-6 m/s: the laws are checked to 1e-6 v0, where the default tolerance
// (1e-4 m/s) leaves a strike's velocities 5e-6 v0 from the LCP's answer.
std::vector<double> StrikeRow(const std::string& solver, const std::string& impacts, int row, double mass, double e) {
  testing::MethodSim sim("lcp", {{"solver", solver}, {"impacts", impacts}, {"tolerance", "1e-6"}});
  sim.world.gravity.setZero();
  std::vector<BodyId> ids;
  for (int i = 0; i <= row; ++i) {
    BodySettings s;
    s.shape = ShapeType::kSphere;
    s.radius = kRadius;
    s.mass = mass;
    s.position = Vec3(2 * kRadius * i, 0, 0);
    s.linear_velocity = Vec3(i == 0 ? kV0 : 0.0, 0, 0);
    s.restitution = e;
    s.friction = 0.0;
    ids.push_back(testing::AddValidBody(sim.world, s));
  }
  while (sim.world.time < 0.05) sim.Step();
  std::vector<double> v;
  for (BodyId id : ids) v.push_back(sim.world.Find(id)->LinearVelocity().x());
  return v;
}

using ImpactParam = std::tuple<const char*, double>;  // solver, mass (kg)

class LcpImpactsTest : public ::testing::TestWithParam<ImpactParam> {};

// Verifies impacts = simultaneous: one LCP with v_n+ >= -e v_n- per contact.
// For three equal spheres with e = 1 only the first pair approaches, so
// (masses 1) v1 - v0 >= v0 and v2 - v1 >= 0, both active: impulses
// j01 = 4/3 v0 and j12 = 2/3 v0, the striker leaves at -v0 / 3 and the
// others together at 2/3 v0 (the energy is kept: 1/9 + 4/9 + 4/9 = 1).
TEST_P(LcpImpactsTest, SimultaneousLawSpreadsTheStrike) {
  const auto [solver, mass] = GetParam();
  const std::vector<double> v = StrikeRow(solver, "simultaneous", 2, mass, 1.0);
  const double expected[] = {-kV0 / 3, 2 * kV0 / 3, 2 * kV0 / 3};
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[i], expected[i], 1e-6 * kV0) << "sphere " << i;
}

// Verifies impacts = sequential (the default): the one-at-a-time outcome of
// line_impacts.h for rows of 2 and 5 and e = 1, 0.5 and 0.2 (Newton's
// cradle at e = 1), within 1e-3 v0.
TEST_P(LcpImpactsTest, SequentialLawTakesTheImpactsOneAtATime) {
  const auto [solver, mass] = GetParam();
  for (int row : {2, 5}) {
    for (double e : {1.0, 0.5, 0.2}) {
      const std::vector<double> v = StrikeRow(solver, "sequential", row, mass, e);
      const std::vector<double> expected = testing::StruckLineVelocities(row + 1, kV0, e);
      double worst = 0.0;
      for (int i = 0; i <= row; ++i) worst = std::max(worst, std::abs(v[i] - expected[i]) / kV0);
      std::printf("%s m %g row %d e %.1f: worst %.2e v0\n", solver, mass, row, e, worst);
      EXPECT_LT(worst, 1e-3) << "row " << row << " e " << e;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, LcpImpactsTest,
                         ::testing::Combine(::testing::Values("pgs", "lemke"), ::testing::Values(0.1, 1.0, 10.0)),
                         [](const ::testing::TestParamInfo<ImpactParam>& info) {
                           return std::string(std::get<0>(info.param)) + "_" +
                                  std::to_string(static_cast<int>(std::get<1>(info.param) * 10)) + "hg";
                         });

}  // namespace
}  // namespace contactsim
