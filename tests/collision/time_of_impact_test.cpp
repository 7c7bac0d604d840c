#include "service/collision/time_of_impact.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "service/physics/math.h"

namespace contactsim {
namespace {

// 0.1 mm: the default contact tolerance, well under any body size here.
constexpr double kTolerance = 1e-4;
// Round-off of a distance of ~1 m computed from positions of ~1 m.
constexpr double kRoundOff = 1e-12;

struct Case {
  std::string name;
  DistanceFunction distance;
  double t0;
  double dt;
  bool typical;  // a motion a contact step sees (smooth, mildly curved over the step)
};

// Smooth approaches seen by an impulse method within one step. Each has a
// single root in (t0, t0 + dt) and is separated at t0.
std::vector<Case> Cases() {
  const double g = 9.81, r = 0.1;
  return {
      // sphere falling at 3 m/s onto a plane, no gravity: d linear
      {"linear", [](double t) { return 0.5 - 3.0 * t; }, 0.0, 0.5, true},
      // sphere dropped from 1 m under gravity, step of 1 s
      {"falling", [=](double t) { return 1.0 - r - 0.5 * g * t * t; }, 0.0, 1.0, true},
      // thrown up at 2 m/s from 0.3 m, coming down late in a long step
      {"thrown", [=](double t) { return 0.3 - r + 2.0 * t - 0.5 * g * t * t; }, 0.1, 0.6, true},
      // corner of a 1 m box spinning at 4 rad/s about a horizontal axis,
      // centre 0.6 m above the plane: the corner drops as the box turns
      {"spinning", [](double t) { return 0.6 - 0.5 * std::sqrt(2.0) * std::sin(M_PI / 4 + 4.0 * t); }, 0.0, 0.15,
       true},
      // adversarial: the distance flattens out just above the root, where
      // false position creeps from one end even with the Illinois halving
      {"exponential", [](double t) { return std::exp(-8.0 * t) - 0.01; }, 0.0, 1.0, false},
  };
}

TimeOfImpactResult Solve(const Case& c, RootFinder finder) {
  TimeOfImpactOptions options;
  options.finder = finder;
  options.tolerance = kTolerance;
  return FindTimeOfImpact(c.distance, c.t0, c.dt, options);
}

// Signed distance (m) from a sphere of radius r centred at p to a box of
// half extents h at the origin: the exact point-box distance minus r
// (negative inside the box by the distance to the nearest face).
double SphereBoxDistance(const Vec3& p, double r, const Vec3& h) {
  const Vec3 q = p.cwiseAbs() - h;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside - r;
}

// Verifies both root finders find a time within tolerance of the target on
// every case, and regula falsi (Illinois) uses fewer evaluations on every
// typical case and in total.
TEST(TimeOfImpactTest, RegulaFalsiNeedsFewerEvaluationsThanBisection) {
  int total_bisection = 0, total_regula = 0;
  std::printf("%-12s %22s %22s\n", "case", "bisection iter/evals", "regula_falsi iter/evals");
  for (const Case& c : Cases()) {
    const TimeOfImpactResult bis = Solve(c, RootFinder::kBisection);
    const TimeOfImpactResult reg = Solve(c, RootFinder::kRegulaFalsi);
    for (const TimeOfImpactResult& r : {bis, reg}) {
      EXPECT_TRUE(r.hit) << c.name;
      EXPECT_TRUE(r.converged) << c.name;
      EXPECT_GT(r.time, c.t0) << c.name;
      EXPECT_LE(r.time, c.t0 + c.dt) << c.name;
      EXPECT_LE(std::abs(c.distance(r.time)), kTolerance) << c.name;
      EXPECT_DOUBLE_EQ(r.distance, c.distance(r.time)) << c.name;
    }
    std::printf("%-12s %14d/%-7d %14d/%-7d\n", c.name.c_str(), bis.iterations, bis.evaluations, reg.iterations,
                reg.evaluations);
    if (c.typical) {
      EXPECT_LT(reg.evaluations, bis.evaluations) << c.name;
    }
    total_bisection += bis.evaluations;
    total_regula += reg.evaluations;
  }
  std::printf("%-12s %22d %22d\n", "total", total_bisection, total_regula);
  EXPECT_LT(total_regula, total_bisection);
}

// Verifies a pair already within tolerance at t0 is a hit at t0 after one
// evaluation, and a pair that stays apart is no hit, reported at t0 + dt.
TEST(TimeOfImpactTest, TouchingAtStartAndSeparatedThroughout) {
  TimeOfImpactOptions options;
  TimeOfImpactResult r = FindTimeOfImpact([](double) { return 0.5e-4; }, 2.0, 0.01, options);
  EXPECT_TRUE(r.hit);
  EXPECT_EQ(r.time, 2.0);
  EXPECT_EQ(r.evaluations, 1);
  r = FindTimeOfImpact([](double t) { return 1.0 - t; }, 0.0, 0.01, options);
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.time, 0.01);
  EXPECT_EQ(r.evaluations, 2);
}

// Verifies a nonzero target (a contact margin) is what the distance comes
// down to.
TEST(TimeOfImpactTest, StopsAtTheTargetDistance) {
  TimeOfImpactOptions options;
  options.target = 0.01;
  const TimeOfImpactResult r = FindTimeOfImpact([](double t) { return 1.0 - 2.0 * t * t; }, 0.0, 1.0, options);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.distance, 0.01, options.tolerance);
  EXPECT_NEAR(r.time, std::sqrt(0.99 / 2.0), options.tolerance);
}

// Verifies a sphere at 100 m/s against a 1 cm thick box is caught before it
// tunnels: checking only the end of the step misses it (both ends are
// 0.445 m apart from the box), while the closing-speed bound finds the first
// touch, never overlapping, for both root finders and for loose bounds.
TEST(TimeOfImpactTest, FastSphereDoesNotTunnelThroughThinBox) {
  const double r = 0.05, speed = 100.0, dt = 0.01;  // the sphere moves 1 m in the step
  const Vec3 h(0.005, 0.5, 0.5);                     // 1 cm thick wall
  const Vec3 p0(-0.5, 0.1, 0.0), v(speed, 0.0, 0.0);
  const DistanceFunction distance = [&](double t) { return SphereBoxDistance(p0 + v * t, r, h); };
  ASSERT_GT(distance(dt), 0.0);  // past the wall at the end of the step

  TimeOfImpactOptions options;
  options.tolerance = kTolerance;
  EXPECT_FALSE(FindTimeOfImpact(distance, 0.0, dt, options).hit);

  const double t_exact = (0.5 - h.x() - r) / speed;
  for (RootFinder finder : {RootFinder::kBisection, RootFinder::kRegulaFalsi}) {
    for (double bound : {speed, 1.5 * speed, 10.0 * speed}) {
      options.finder = finder;
      options.max_closing_speed = bound;
      const TimeOfImpactResult res = FindTimeOfImpact(distance, 0.0, dt, options);
      ASSERT_TRUE(res.hit) << RootFinderName(finder) << " bound " << bound;
      EXPECT_TRUE(res.converged);
      // within tolerance of the target, on the safe side: at most tol / speed early
      EXPECT_GE(res.distance, -kRoundOff);
      EXPECT_LE(res.distance, kTolerance);
      EXPECT_LE(res.time, t_exact + kRoundOff / speed);
      EXPECT_GE(res.time, t_exact - kTolerance / speed);
      std::printf("%-12s bound %6.0f m/s: t = %.7f s (exact %.7f), %d advancement steps, %d evaluations\n",
                  RootFinderName(finder), bound, res.time, t_exact, res.advancement_steps, res.evaluations);
    }
  }
}

// Verifies a bound that is too small (not a bound) still gives a hit inside
// the bracket it overshot into, refined by the root finder.
TEST(TimeOfImpactTest, UnderestimatedSpeedBoundStillFindsTheHit) {
  const DistanceFunction distance = [](double t) { return 0.5 - 10.0 * t; };
  TimeOfImpactOptions options;
  options.max_closing_speed = 2.0;  // true closing speed is 10 m/s
  const TimeOfImpactResult r = FindTimeOfImpact(distance, 0.0, 0.1, options);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.time, 0.05, options.tolerance / 10.0);
}

// Verifies a discontinuous distance (a step) is resolved to the last safe
// time without looping.
TEST(TimeOfImpactTest, StepDistanceResolvesToMachinePrecision) {
  const DistanceFunction distance = [](double t) { return t < 0.3 ? 1.0 : -1.0; };
  for (RootFinder finder : {RootFinder::kBisection, RootFinder::kRegulaFalsi}) {
    TimeOfImpactOptions options;
    options.finder = finder;
    const TimeOfImpactResult r = FindTimeOfImpact(distance, 0.0, 1.0, options);
    ASSERT_TRUE(r.hit);
    EXPECT_LT(r.time, 0.3);
    EXPECT_NEAR(r.time, 0.3, 1e-12);
    EXPECT_EQ(r.distance, 1.0);
  }
}

// Verifies root finder names round-trip and bad names and options are
// rejected with messages naming the field and value.
TEST(TimeOfImpactTest, NamesAndOptionsAreValidated) {
  RootFinder finder = RootFinder::kBisection;
  ASSERT_TRUE(ParseRootFinder("regula_falsi", &finder).ok());
  EXPECT_EQ(finder, RootFinder::kRegulaFalsi);
  ASSERT_TRUE(ParseRootFinder(RootFinderName(RootFinder::kBisection), &finder).ok());
  EXPECT_EQ(finder, RootFinder::kBisection);
  Status s = ParseRootFinder("newton", &finder);
  EXPECT_EQ(s.message(), "unknown root finder \"newton\"; known: bisection, regula_falsi");

  TimeOfImpactOptions options;
  EXPECT_TRUE(ValidateTimeOfImpactOptions(options).ok());
  options.tolerance = -1.0;
  EXPECT_EQ(ValidateTimeOfImpactOptions(options).message(),
            "time of impact tolerance must be positive and finite, got -1");
  options = TimeOfImpactOptions();
  options.max_iterations = 0;
  EXPECT_EQ(ValidateTimeOfImpactOptions(options).message(), "time of impact max_iterations must be positive, got 0");
  options = TimeOfImpactOptions();
  options.max_closing_speed = std::nan("");
  EXPECT_EQ(ValidateTimeOfImpactOptions(options).code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace contactsim
