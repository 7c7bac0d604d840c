// Tests of PGS swept colour by colour on a ParallelRunner (pgs_stages.cpp):
// the same answer bit for bit on any number of threads, and the LCP's
// answer when it converges.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cmath>
#include <random>
#include <vector>

#include "service/contact/lcp/delassus.h"
#include "service/contact/lcp/lemke.h"
#include "service/contact/lcp/pgs.h"

namespace contactsim {
namespace {

Vec3 RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Vec3(normal(rng), normal(rng), normal(rng)).normalized();
}

// `bodies` free bodies (mass 0.1-10 kg) moving at random, the first 5%
// static, and `contacts` contacts between random pairs (some on the world,
// -1), each a normal row and a friction pair as the lcp method builds
// them (mu 0.5), with random warm-start impulses.
struct Problem {
  std::vector<SolverBody> bodies;
  std::vector<ConstraintRow> rows;
};

Problem RandomContacts(std::mt19937& rng, int bodies, int contacts) {
  std::uniform_real_distribution<double> mass(0.1, 10.0), unit(0.0, 1.0);
  std::uniform_int_distribution<int> body(-1, bodies - 1), points(1, 4);
  Problem p;
  p.bodies.resize(bodies);
  for (int i = 0; i < bodies; ++i) {
    SolverBody& b = p.bodies[i];
    const double m = mass(rng);
    b.inv_mass = i < bodies / 20 ? 0.0 : 1.0 / m;
    b.inv_inertia = i < bodies / 20 ? Mat3::Zero() : Mat3(Vec3::Constant(6.0 / m).asDiagonal());
    b.v = 2.0 * RandomUnit(rng);
    b.w = RandomUnit(rng);
  }
  for (int c = 0; c < contacts;) {
    const int a = body(rng);
    int b = body(rng);
    if (b == a || b < 0) continue;
    const Vec3 n = RandomUnit(rng);
    Vec3 t1, t2;
    PerpendicularBasis(n, &t1, &t2);
    for (int k = points(rng); k > 0 && c < contacts; --k, ++c) {  // a pair's points in a row
      const Vec3 ra = 0.1 * RandomUnit(rng), rb = 0.1 * RandomUnit(rng);
      const int normal = static_cast<int>(p.rows.size());
      for (const Vec3& d : {n, t1, t2}) {
        ConstraintRow r;
        r.a = a, r.b = b;
        if (a >= 0) r.lin_a = -d, r.ang_a = -ra.cross(d);
        r.lin_b = d, r.ang_b = rb.cross(d);
        r.lambda = 0.05 * unit(rng);
        if (d == n) {
          r.lo = 0.0;
          r.rhs = 0.01 * unit(rng);
        } else {
          r.normal_row = normal;
          r.mu = 0.5;
        }
        p.rows.push_back(r);
      }
    }
  }
  return p;
}

// Verifies that the coloured sweep gives the same impulses, velocities,
// sweep count and residual bit for bit on 1, 2 and 4 threads, for 400
// bodies and 1,500 contacts, stopped by the tolerance (the later sweeps'
// stages then do nothing) and by the sweep cap.
TEST(PgsStages, SameAnswerOnAnyNumberOfThreads) {
  oneapi::tbb::global_control allow(oneapi::tbb::global_control::max_allowed_parallelism, 4);
  std::mt19937 rng(31);
  const Problem problem = RandomContacts(rng, 400, 1500);
  // a tolerance just above the third sweep's change stops at the third
  // sweep at the latest; 1e-12 m/s runs all 40
  double third = 0.0;
  {
    Problem p = problem;
    ParallelRunner one(1);
    PgsOptions options;
    options.iterations = 3;
    options.tolerance = 0.0;
    options.runner = &one;
    third = PgsSolver().Solve(p.rows, p.bodies, options).residual;
  }
  for (const double tolerance : {third * (1.0 + 1e-9), 1e-12}) {
    Problem serial = problem;
    ParallelRunner one(1);
    PgsOptions options;
    options.iterations = 40;
    options.tolerance = tolerance;
    options.runner = &one;
    PgsSolver pgs;
    const SolveReport expected = pgs.Solve(serial.rows, serial.bodies, options);
    EXPECT_EQ(expected.converged, tolerance > 1e-6) << "tolerance " << tolerance;
    EXPECT_LE(expected.iterations, tolerance > 1e-6 ? 3 : 40) << "tolerance " << tolerance;
    EXPECT_GE(expected.iterations, tolerance > 1e-6 ? 2 : 40) << "tolerance " << tolerance;
    for (const int threads : {2, 4}) {
      Problem p = problem;
      ParallelRunner runner(threads);
      options.runner = &runner;
      const SolveReport report = pgs.Solve(p.rows, p.bodies, options);
      EXPECT_EQ(report.iterations, expected.iterations) << threads << " threads";
      EXPECT_EQ(report.residual, expected.residual) << threads << " threads";
      for (size_t k = 0; k < p.rows.size(); ++k) {
        ASSERT_EQ(p.rows[k].lambda, serial.rows[k].lambda) << "row " << k << ", " << threads << " threads";
      }
      for (size_t i = 0; i < p.bodies.size(); ++i) {
        ASSERT_EQ(p.bodies[i].v, serial.bodies[i].v) << "body " << i << ", " << threads << " threads";
        ASSERT_EQ(p.bodies[i].w, serial.bodies[i].w) << "body " << i << ", " << threads << " threads";
        ASSERT_EQ(p.bodies[i].dP, serial.bodies[i].dP) << "body " << i << ", " << threads << " threads";
      }
    }
  }
}

// Verifies that the coloured sweep on 2 threads converges to Lemke's
// answer on positive definite problems (frictionless rows between 8 bodies
// with random Jacobians, 100 problems, impulses equal to 1e-6 relative), as
// the serial sweep does (lcp_pgs_test.cpp): the order of a Gauss-Seidel
// sweep changes its path, not its fixed point.
TEST(PgsStages, ConvergesToLemkesAnswer) {
  std::mt19937 rng(41);
  std::normal_distribution<double> normal;
  ParallelRunner runner(2);
  for (int trial = 0; trial < 100; ++trial) {
    Problem p = RandomContacts(rng, 8, 0);
    for (SolverBody& b : p.bodies) b.inv_mass = 1.0, b.inv_inertia = Mat3::Identity();
    for (int k = 0; k < 12; ++k) {
      ConstraintRow r;
      r.a = k % 8;
      r.b = (k * 3 + 1) % 8 == r.a ? -1 : (k * 3 + 1) % 8;
      r.lin_a = RandomUnit(rng), r.ang_a = RandomUnit(rng), r.lin_b = RandomUnit(rng), r.ang_b = RandomUnit(rng);
      r.rhs = normal(rng);
      r.lo = 0.0;
      p.rows.push_back(r);
    }
    const MatX G = DenseDelassus(p.rows, p.bodies);
    VecX q = RowVelocities(p.rows, p.bodies);
    for (int k = 0; k < 12; ++k) q[k] -= p.rows[k].rhs;
    const LcpSolution exact = SolveLemke(G, q);
    ASSERT_EQ(exact.outcome, LcpOutcome::kSolved);
    PgsSolver pgs;
    PgsOptions options;
    options.iterations = 20000;
    options.tolerance = 1e-13;
    options.runner = &runner;
    const SolveReport report = pgs.Solve(p.rows, p.bodies, options);
    EXPECT_TRUE(report.converged) << "trial " << trial;
    double err = 0.0;
    for (int k = 0; k < 12; ++k) err = std::max(err, std::abs(p.rows[k].lambda - exact.z[k]));
    EXPECT_LT(err, 1e-6 * std::max(1.0, exact.z.cwiseAbs().maxCoeff())) << "trial " << trial;
  }
}

}  // namespace
}  // namespace contactsim
