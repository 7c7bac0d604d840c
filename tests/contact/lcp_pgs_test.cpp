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

namespace contactsim {
namespace {

// The four normal rows of a box's bottom face (half extents hx, hy, hz,
// body 0) on the world, in the order `corner_order` (indices into the
// corners (-,-), (+,-), (+,+), (-,+)), and the block that names them.
std::vector<ConstraintRow> FaceOnGround(double hx, double hy, double hz, const int corner_order[4],
                                        std::vector<PgsNormalBlock>* blocks) {
  const Vec3 corners[4] = {{-hx, -hy, -hz}, {hx, -hy, -hz}, {hx, hy, -hz}, {-hx, hy, -hz}};
  std::vector<ConstraintRow> rows(4);
  PgsNormalBlock blk;
  blk.count = 4;
  for (int k = 0; k < 4; ++k) {
    rows[k].b = 0;
    rows[k].lin_b = Vec3::UnitZ();
    rows[k].ang_b = corners[corner_order[k]].cross(Vec3::UnitZ());
    rows[k].lo = 0.0;
    blk.rows[k] = k;
  }
  blocks->assign(1, blk);
  return rows;
}

SolverBody BoxBody(double mass, double hx, double hy, double hz) {
  SolverBody b;
  b.inv_mass = 1.0 / mass;
  const Vec3 i = mass / 3.0 * Vec3(hy * hy + hz * hz, hx * hx + hz * hz, hx * hx + hy * hy);
  b.inv_inertia = i.cwiseInverse().asDiagonal();
  return b;
}

// Verifies that one PGS sweep stops a box landing flat at 1 m/s with the
// face's four normal rows as a block: each corner takes m v / 4 (to 1e-9) and
// the box does not turn, for masses 0.1-10 kg, square and oblong faces and
// any order of the corners (K is singular: four rows on three velocities;
// the block's pseudo-inverse gives the least-norm, symmetric answer).
// Swept row by row, the first corner takes more and the box turns.
TEST(Pgs, NormalBlockGivesAFlatFaceFourEqualImpulsesInOneSweep) {
  const int orders[3][4] = {{0, 1, 2, 3}, {2, 0, 3, 1}, {3, 1, 0, 2}};
  for (double mass : {0.1, 1.0, 10.0}) {
    for (const Vec3& half : {Vec3(0.1, 0.1, 0.1), Vec3(0.3, 0.05, 0.2), Vec3(1e-3, 2.0, 0.5)}) {
      for (const auto& order : orders) {
        std::vector<PgsNormalBlock> blocks;
        std::vector<ConstraintRow> rows = FaceOnGround(half.x(), half.y(), half.z(), order, &blocks);
        std::vector<SolverBody> bodies = {BoxBody(mass, half.x(), half.y(), half.z())};
        bodies[0].v = Vec3(0, 0, -1);
        PgsSolver pgs;
        PgsOptions options;
        options.iterations = 1;
        options.normal_blocks = &blocks;
        pgs.Solve(rows, bodies, options);
        for (const ConstraintRow& r : rows) EXPECT_NEAR(r.lambda, mass / 4.0, 1e-9 * mass);
        EXPECT_NEAR(bodies[0].v.z(), 0.0, 1e-9);
        EXPECT_LT(bodies[0].w.norm(), 1e-9) << "mass " << mass << " half " << half.transpose();
      }
    }
  }
  // without the block
  const int order[4] = {0, 1, 2, 3};
  std::vector<PgsNormalBlock> unused;
  std::vector<ConstraintRow> rows = FaceOnGround(0.1, 0.1, 0.1, order, &unused);
  std::vector<SolverBody> bodies = {BoxBody(1.0, 0.1, 0.1, 0.1)};
  bodies[0].v = Vec3(0, 0, -1);
  PgsSolver pgs;
  PgsOptions options;
  options.iterations = 1;
  pgs.Solve(rows, bodies, options);
  EXPECT_GT(bodies[0].w.norm(), 0.1);
}

// Verifies that a block with a corner lifting off falls back to the rows
// one by one and still reaches the LCP's answer: a box landing on one edge
// while it turns (v_z = -1 m/s, w_x = 20 rad/s lifts the y > 0 corners),
// 200 sweeps, against Lemke's velocities (the impulses are not unique, the
// velocities are).
TEST(Pgs, NormalBlockWithALiftingCornerReachesLemkesVelocities) {
  const int order[4] = {0, 1, 2, 3};
  std::vector<PgsNormalBlock> blocks;
  std::vector<ConstraintRow> rows = FaceOnGround(0.2, 0.1, 0.1, order, &blocks);
  std::vector<ConstraintRow> lemke_rows = rows;
  std::vector<SolverBody> bodies = {BoxBody(2.0, 0.2, 0.1, 0.1)};
  bodies[0].v = Vec3(0, 0, -1);
  bodies[0].w = Vec3(20, 0, 0);
  std::vector<SolverBody> lemke_bodies = bodies;
  PgsSolver pgs;
  PgsOptions options;
  options.iterations = 200;
  options.tolerance = 1e-13;
  options.normal_blocks = &blocks;
  pgs.Solve(rows, bodies, options);
  SolveReport report;
  ASSERT_TRUE(SolveRowsLemke(lemke_rows, lemke_bodies, {}, &report).ok());
  EXPECT_NEAR((bodies[0].v - lemke_bodies[0].v).norm(), 0.0, 1e-9);
  EXPECT_NEAR((bodies[0].w - lemke_bodies[0].w).norm(), 0.0, 1e-9);
  for (int k : {2, 3}) EXPECT_EQ(rows[k].lambda, 0.0) << "corner " << k << " lifts off";
}

}  // namespace
}  // namespace contactsim
