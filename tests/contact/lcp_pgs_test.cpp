// Tests of projected Gauss-Seidel on constraint rows against Lemke's exact
// answer, and of the Lemke row solver's friction form.
#include "service/contact/lcp/pgs.h"

#include <gtest/gtest.h>

#include <cmath>
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
    b.inv_inertia = Vec3{1.0 / u(rng), 1.0 / u(rng), 1.0 / u(rng)}.asDiagonal();
    b.v = Vec3{normal(rng), normal(rng), normal(rng)};
    b.w = Vec3{normal(rng), normal(rng), normal(rng)};
  }
  return bodies;
}

Vec3 RandomVec(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  return Vec3{normal(rng), normal(rng), normal(rng)};
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

// One contact point of a unit-mass body on the world with its friction rows
// along t1 and n x t1.
std::vector<ConstraintRow> PointOnGround(double mu, const Vec3& t1) {
  std::vector<ConstraintRow> rows = PointOnGround(mu);
  rows[1].lin_b = t1;
  rows[2].lin_b = Vec3::UnitZ().cross(t1);
  return rows;
}

// Verifies Coulomb's law in both solvers on a point mass landing at
// vz = -1 m/s (normal impulse m 1 N s) with mu = 0.3: sliding at
// (2, 0.1) m/s it loses mu 1 = 0.3 m/s along its slip, and at (0.2, 0.1)
// m/s (|v| < mu) it sticks. PGS projects onto the disk, so its answer does
// not depend on the tangents (the contact frame's x, y here, 45 degrees
// off); Lemke's pyramid is exact with t1 along the slip, as the lcp method
// builds its rows (lcp_contact_rows.h).
TEST(Pgs, FrictionMatchesCoulombInBothSolvers) {
  const double mu = 0.3;
  for (double vx : {2.0, 0.2}) {
    const Vec3 slip(vx, 0.1, 0.0);
    const Vec3 expected = slip.norm() > mu ? Vec3(slip * (1.0 - mu / slip.norm())) : Vec3::Zero();
    for (const char* solver : {"pgs", "pgs_diagonal", "lemke"}) {
      std::vector<SolverBody> bodies(1);
      bodies[0].inv_mass = 1.0;
      bodies[0].inv_inertia = Mat3::Identity();
      bodies[0].v = Vec3(vx, 0.1, -1.0);
      const std::string name = solver;
      std::vector<ConstraintRow> rows =
          name == "pgs" ? PointOnGround(mu)
                        : PointOnGround(mu, name == "lemke" ? Vec3(slip.normalized()) : Vec3(1, 1, 0).normalized());
      SolveReport report;
      if (name != "lemke") {
        PgsSolver pgs;
        PgsOptions options;
        options.iterations = 100;
        options.tolerance = 1e-12;
        report = pgs.Solve(rows, bodies, options);
      } else {
        ASSERT_TRUE(SolveRowsLemke(rows, bodies, {}, &report).ok());
      }
      ASSERT_TRUE(report.converged) << solver;
      EXPECT_NEAR(rows[0].lambda, 1.0, 1e-9) << solver;
      EXPECT_NEAR(bodies[0].v.z(), 0.0, 1e-9) << solver;
      EXPECT_NEAR(bodies[0].v.x(), expected.x(), 1e-9) << solver << " vx " << vx;
      EXPECT_NEAR(bodies[0].v.y(), expected.y(), 1e-9) << solver << " vx " << vx;
      EXPECT_LT(report.complementarity, 1e-9) << solver;
    }
  }
}

// Verifies that PGS's friction is isotropic: a point mass sliding at 2 m/s
// in any direction of the contact frame's tangent plane loses exactly
// mu lambda_n = 0.3 m/s along its slip (the box of two 1D laws took up
// to sqrt(2) mu lambda_n, diagonally).
TEST(Pgs, FrictionIsTheSameInEveryDirection) {
  const double mu = 0.3, speed = 2.0;
  for (int deg = 0; deg < 360; deg += 15) {
    const double a = deg * 3.14159265358979323846 / 180.0;
    std::vector<SolverBody> bodies(1);
    bodies[0].inv_mass = 1.0;
    bodies[0].inv_inertia = Mat3::Identity();
    bodies[0].v = Vec3(speed * std::cos(a), speed * std::sin(a), -1.0);
    std::vector<ConstraintRow> rows = PointOnGround(mu);
    PgsSolver pgs;
    PgsOptions options;
    options.iterations = 100;
    options.tolerance = 1e-12;
    pgs.Solve(rows, bodies, options);
    const Vec3 v = bodies[0].v;
    EXPECT_NEAR(v.head<2>().norm(), speed - mu, 1e-9) << deg << " deg";
    EXPECT_NEAR(v.x() * std::sin(a) - v.y() * std::cos(a), 0.0, 1e-9) << deg << " deg";  // along the slip
    EXPECT_GT(v.x() * std::cos(a) + v.y() * std::sin(a), 0.0) << deg << " deg";
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
