// Tests of projected Gauss-Seidel on constraint rows against Lemke's exact
// answer, and of the Lemke row solver's friction form.
#include "service/contact/lcp/pgs.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <Eigen/Eigenvalues>
#include <random>
#include <string>

#include "service/contact/lcp/delassus.h"
#include "service/contact/lcp/lemke.h"
#include "service/contact/lcp/lemke_rows.h"

namespace contactsim {
namespace {

// Three free bodies with random mass and inertia and random velocities.
std::vector<SolverBody> RandomBodies(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::normal_distribution<double> normal;
  std::vector<SolverBody> bodies(n);
  for (SolverBody& b : bodies) {
    b.inv_mass = 1.0 / u(rng);
    b.inv_inertia = Vec3(1.0 / u(rng), 1.0 / u(rng), 1.0 / u(rng)).asDiagonal();
    b.v = Vec3(normal(rng), normal(rng), normal(rng));
    b.w = Vec3(normal(rng), normal(rng), normal(rng));
  }
  return bodies;
}

Vec3 RandomVec(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Vec3(normal(rng), normal(rng), normal(rng));
}

// Verifies that PGS converges to Lemke's solution of the same LCP on
// positive definite problems: 8 unilateral rows between 3 bodies (18
// velocities, so G = J M^-1 J^T is positive definite for random J), 100
// problems, impulses equal to 1e-6 relative after at most 5,000 sweeps
// (Gauss-Seidel converges linearly on positive definite LCPs, Cottle, Pang
// and Stone 1992, section 5.2; the tolerance 1e-12 m/s stops it well below
// the comparison).
TEST(Pgs, ConvergesToLemkesAnswerOnPositiveDefiniteProblems) {
  std::mt19937 rng(21);
  int max_iterations = 0;
  double worst = 0.0, worst_residual = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<SolverBody> bodies = RandomBodies(rng, 3);
    std::vector<ConstraintRow> rows(8);
    for (int k = 0; k < 8; ++k) {
      ConstraintRow& r = rows[k];
      r.a = k % 3;
      r.b = (k + 1) % 3 == 0 ? -1 : (k + 1) % 3;  // some rows against the world
      r.lin_a = RandomVec(rng), r.ang_a = RandomVec(rng), r.lin_b = RandomVec(rng), r.ang_b = RandomVec(rng);
      r.rhs = RandomVec(rng).x();
      r.lo = 0.0;
    }
    const MatX G = DenseDelassus(rows, bodies);
    VecX q = RowVelocities(rows, bodies);
    for (int k = 0; k < 8; ++k) q[k] -= rows[k].rhs;
    ASSERT_GT(Eigen::SelfAdjointEigenSolver<MatX>(G).eigenvalues().minCoeff(), 0.0);
    const LcpSolution exact = SolveLemke(G, q);
    ASSERT_EQ(exact.outcome, LcpOutcome::kSolved);

    PgsSolver pgs;
    PgsOptions options;
    options.iterations = 5000;
    options.tolerance = 1e-12;
    const SolveReport report = pgs.Solve(rows, bodies, options);
    EXPECT_TRUE(report.converged) << "trial " << trial;
    double err = 0.0;
    for (int k = 0; k < 8; ++k) err = std::max(err, std::abs(rows[k].lambda - exact.z[k]));
    EXPECT_LT(err, 1e-6 * std::max(1.0, exact.z.cwiseAbs().maxCoeff())) << "trial " << trial;
    EXPECT_LT(report.complementarity, 1e-9);
    worst = std::max(worst, err);
    worst_residual = std::max(worst_residual, report.residual);
    max_iterations = std::max(max_iterations, report.iterations);
  }
  std::printf("PGS vs Lemke: largest impulse difference %.2e N s, at most %d sweeps, residual < %.1e m/s\n",
              worst, max_iterations, worst_residual);
}

// Verifies that warm starting from the answer needs a single sweep.
TEST(Pgs, WarmStartFromTheAnswerConvergesInOneSweep) {
  std::mt19937 rng(22);
  std::vector<SolverBody> bodies = RandomBodies(rng, 2);
  std::vector<ConstraintRow> rows(4);
  for (ConstraintRow& r : rows) {
    r.a = 0, r.b = 1;
    r.lin_a = RandomVec(rng), r.ang_a = RandomVec(rng), r.lin_b = RandomVec(rng), r.ang_b = RandomVec(rng);
    r.lo = 0.0;
    r.rhs = 1.0;
  }
  std::vector<SolverBody> cold = bodies;
  std::vector<ConstraintRow> solved = rows;
  PgsSolver pgs;
  PgsOptions options;
  options.iterations = 10000;
  options.tolerance = 1e-13;
  pgs.Solve(solved, cold, options);
  for (size_t k = 0; k < rows.size(); ++k) rows[k].lambda = solved[k].lambda;
  options.tolerance = 1e-9;
  const SolveReport warm = pgs.Solve(rows, bodies, options);
  EXPECT_EQ(warm.iterations, 1);
  EXPECT_TRUE(warm.converged);
}

// One contact point of a unit-mass body on the world (a = -1), pushed
// sideways: normal row and two friction rows as the lcp method builds them.
std::vector<ConstraintRow> PointOnGround(double mu) {
  std::vector<ConstraintRow> rows(3);
  const Vec3 dirs[3] = {Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()};
  for (int k = 0; k < 3; ++k) {
    rows[k].b = 0;
    rows[k].lin_b = dirs[k];
    rows[k].lo = k == 0 ? 0.0 : -ConstraintRow::kInf;
    rows[k].normal_row = k == 0 ? -1 : 0;
    rows[k].mu = mu;
  }
  return rows;
}

// Verifies the friction pyramid in both solvers against Coulomb's law on a
// point mass landing at vz = -1 m/s: sliding at vx = 2 m/s with mu = 0.3 it
// keeps 2 - mu 1 = 1.7 m/s (the normal impulse is m 1 N s), and at
// vx = 0.2 m/s (below mu) it sticks; vy = 0.1 m/s sticks too (box friction,
// each tangent by itself).
TEST(Pgs, FrictionPyramidMatchesCoulombAndLemke) {
  const double mu = 0.3;
  for (double vx : {2.0, 0.2}) {
    for (const char* solver : {"pgs", "lemke"}) {
      std::vector<SolverBody> bodies(1);
      bodies[0].inv_mass = 1.0;
      bodies[0].inv_inertia = Mat3::Identity();
      bodies[0].v = Vec3(vx, 0.1, -1.0);
      std::vector<ConstraintRow> rows = PointOnGround(mu);
      SolveReport report;
      if (std::string(solver) == "pgs") {
        PgsSolver pgs;
        PgsOptions options;
        options.iterations = 100;
        report = pgs.Solve(rows, bodies, options);
      } else {
        ASSERT_TRUE(SolveRowsLemke(rows, bodies, {}, &report).ok());
      }
      ASSERT_TRUE(report.converged) << solver;
      EXPECT_NEAR(rows[0].lambda, 1.0, 1e-9) << solver;
      EXPECT_NEAR(bodies[0].v.z(), 0.0, 1e-9) << solver;
      EXPECT_NEAR(bodies[0].v.x(), vx > mu ? vx - mu : 0.0, 1e-9) << solver << " vx " << vx;
      EXPECT_NEAR(bodies[0].v.y(), 0.0, 1e-9) << solver;
      EXPECT_LT(report.complementarity, 1e-9) << solver;
    }
  }
}

// Verifies an upper-limit row (lambda <= 0, as a joint's upper limit) in
// both solvers: it stops motion along +x (lambda = -m v) and lets motion
// along -x go (lambda = 0).
TEST(Pgs, UpperLimitRowPushesOneWayInBothSolvers) {
  for (double vx : {1.0, -1.0}) {
    for (const char* solver : {"pgs", "lemke"}) {
      std::vector<SolverBody> bodies(1);
      bodies[0].inv_mass = 0.5;
      bodies[0].inv_inertia = Mat3::Identity();
      bodies[0].v = Vec3(vx, 0, 0);
      std::vector<ConstraintRow> rows(1);
      rows[0].b = 0;
      rows[0].lin_b = Vec3::UnitX();
      rows[0].lo = -ConstraintRow::kInf;
      rows[0].hi = 0.0;
      SolveReport report;
      if (std::string(solver) == "pgs") {
        PgsSolver pgs;
        report = pgs.Solve(rows, bodies, PgsOptions());
      } else {
        ASSERT_TRUE(SolveRowsLemke(rows, bodies, {}, &report).ok());
      }
      EXPECT_NEAR(rows[0].lambda, vx > 0 ? -2.0 * vx : 0.0, 1e-12) << solver << " vx " << vx;
      EXPECT_NEAR(bodies[0].v.x(), vx > 0 ? 0.0 : vx, 1e-12) << solver << " vx " << vx;
    }
  }
}

}  // namespace
}  // namespace contactsim
