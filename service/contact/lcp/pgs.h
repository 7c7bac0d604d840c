// Projected Gauss-Seidel on constraint rows, in body-velocity form
// (Erleben, "Velocity-based shock propagation for multibody dynamics
// animation", ACM TOG 2007; Catto, "Iterative dynamics with temporal
// coherence", GDC 2005; Andrews, Erleben and Ferguson, SIGGRAPH 2022
// course, section 6).
//
// The LCP w = A lambda + b with A = J M^-1 J^T is never formed: a sweep
// visits each row k once and sets
//   lambda_k <- clamp(lambda_k + (rhs_k - J_k v) / A_kk, lo_k, hi_k),
//   v        <- v + M^-1 J_k^T (change of lambda_k),
// which is Gauss-Seidel on A with projection onto the bounds (a compliant
// row, a joint's damping, aims at J v + cfm lambda = rhs: A_kk + cfm and
// rhs_k - cfm lambda_k in place of A_kk and rhs_k). Rows come in
// with lambda as the warm start (last step's impulses), which is applied
// first.
//
// Friction: a contact's two friction rows (a friction pair,
// friction_disk.h) are one block, updated together at the first row's
// place in the sweep (the rows between them touch other bodies, so this is
// the same sweep) and projected onto the Coulomb disk
//   lambda_t <- P_disk(lambda_t + eta (rhs_t - J_t v)),  eta = 2 / tr(A_tt),
//   |lambda_t| <= mu lambda_n (lambda_n: the normal row's current impulse),
// the block step of Tasora and Anitescu ("A matrix-free cone
// complementarity approach for solving large-scale, nonsmooth, rigid body
// dynamics", CMAME 2011, eq. 31, with the 2x2 tangential block). One scalar
// step for both rows makes a sliding fixed point lambda_t = -mu lambda_n
// u / |u| opposite the slip u (maximal dissipation); a step per row (or the
// 2x2 inverse) would tilt it by the block's anisotropy, and clamping each
// row to +-mu lambda_n (ODE's boxed pyramid) lets diagonal sliding feel up
// to sqrt(2) mu lambda_n. 2 / tr is the optimal fixed gradient step for the
// block, 2 / (its two eigenvalues' sum). A friction row without a partner
// keeps the scalar clamp to +-mu lambda_n.
//
// Normal blocks: the normal rows of one contact pair with one normal (up to
// four points, PgsOptions::normal_blocks) are updated together at the
// place of the first of them in the sweep, lambda += K^+ (rhs - J v), kept
// when every impulse stays >= 0 and otherwise row by row (normal_block.h):
// swept one by one, a face's first corner takes more than its share and an
// aligned stack walks. The pair's rows sit together in the caller's order,
// so no row between them in the schedule touches either body.
//
// Warm-started solves, one a step: the warm start applies last step's
// impulses in full, the part that corrected last step's velocity error
// included, so the next solve must take that part back. For a mode that a
// sweep over-relaxes (a sweep multiplies its error by c = 1 - omega with
// omega > 1: the friction step eta = 2 / tr(A_tt) over-relaxes the stiffer
// tangent of an anisotropic pair by up to 2 lambda_max / tr), m sweeps a
// step leave error and impulse evolving over the steps by a map of
// eigenvalues c^m +- sqrt(c^2m - c^m); with one sweep and c < -1/3 one of
// them lies beyond -1, and the mode grows until a sweep changes a row
// velocity by more than the tolerance and a second sweep knocks it back:
// a resting tetrahedron rocked at the tolerance, 1e-6 m/s, with tolerance
// 1e-12 at 1e-12 m/s. With two sweeps c^m >= 0 and the map contracts
// (|eigenvalue|^2 = c^m < 1), so PgsOptions::min_iterations = 2 lets the
// same body settle to round-off (docs/methods/lcp.md, "Resting hulls").
//
// Reported per solve:
//   residual        m/s, the largest change of a row velocity J_k v made by
//                   the last sweep (|change of lambda_k| A_kk); the solve
//                   stops when it falls below the tolerance;
//   complementarity J, ComplementarityError of the rows after the solve
//                   (row_complementarity.h): zero exactly at a solution;
//                   0 when PgsOptions::measure_complementarity is off.
//
// Performance: rows are copied once per solve into a flat array holding
// J and M^-1 J^T (so the sweep does no 3x3 products) and the reciprocal of
// A_kk, in the order of RowSchedule (row_schedule.h): consecutive rows
// touch different bodies, so their updates do not wait on each other's
// velocity stores. Velocities live in a dense array of (v, w) per body plus
// one zero-velocity slot for the world and a write-only slot (one per group
// of rows, so that no two threads write one) where rows put the
// (unchanged) velocity of a body without mass, so a sweep is
// branch-free, allocation-free (the workspace is reused between solves)
// and carries no false dependency through a static body's velocity.
//
// Threads (PgsOptions::runner): the rows are swept colour by colour
// (row_schedule.h, Colour) as the stages of one ParallelRunner::Stages
// call, the warm start and every sweep a pass over the colours and a
// serial stage after each sweep that takes the largest change of the
// sweep's groups and decides whether to stop; the sweeps after that do
// nothing. A colour's groups share no moving body and each group writes
// its own sink, so the result is the same bit for bit on any number of
// threads (docs/architecture.md, "Threads"); it is not the result of the
// serial sweep in the caller's order, which a solve without a runner keeps.
#pragma once

#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/block_colours.h"
#include "service/contact/constraint_row.h"
#include "service/contact/normal_block.h"
#include "service/contact/lcp/row_schedule.h"
#include "service/contact/lcp/solve_report.h"

namespace contactsim {

// The caller's indices of the normal rows of one pair's points.
struct PgsNormalBlock {
  int rows[kMaxNormalBlock] = {-1, -1, -1, -1};
  int count = 0;
};

struct PgsOptions {
  int iterations = 30;        // sweeps at most
  int min_iterations = 1;     // sweeps at least (2 for warm-started solves a step, see above)
  double tolerance = 1e-6;    // m/s: stop when no row velocity changes more in a sweep
  const std::vector<PgsNormalBlock>* normal_blocks = nullptr;  // none: every row alone
  ParallelRunner* runner = nullptr;  // sweep colour by colour on its threads; none: serially in the caller's order
  // with a runner: rows from this index on (joints'), and the rows on their
  // bodies, keep the caller's order after the colours (row_schedule.h); -1: none
  int ordered_from = -1;
  // SolveReport::complementarity, a pass over every row after the solve;
  // false leaves it 0 (a caller that does not read it)
  bool measure_complementarity = true;
};

class PgsSolver {
 public:
  // Solves for rows' lambda (warm start in, result out) and adds the
  // impulses to the bodies (v, w, dP, dL as ConstraintRow::Apply does).
  SolveReport Solve(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies, const PgsOptions& options);

 private:
  struct Row {
    int a, b;                     // velocity slots read (the world: the zero slot)
    int write_a, write_b;         // velocity slots written (the sink for bodies without mass)
    Vec3 ja_lin, ja_ang, jb_lin, jb_ang;
    Vec3 ma_lin, ma_ang, mb_lin, mb_ang;  // M^-1 J^T
    double diag, inv_diag;
    double rhs, lo, hi, mu, lambda;
    double cfm;                   // compliance (a joint's damping row), 0 for rigid rows
    int normal_row;               // in rows_ order
    int second;                   // first row of a friction pair: the second's index in rows_, else -1
    bool in_pair;                 // second row of a friction pair (updated with the first)
    int block;                    // first row of a normal block: its index in blocks_, else -1
    bool in_block;                // a later row of a normal block (updated with the first)
    int source;                   // index in the caller's rows
  };
  struct Block {
    int rows[kMaxNormalBlock];    // in rows_ order, the first one first
    int count;
    Eigen::Matrix4d inv_k;
  };
  struct Velocity {
    Vec3 v, w;
  };
  // Writes the velocities A, B of the row's bodies plus M^-1 J^T d to the
  // row's write slots (a body without mass: to the sink, which nothing reads).
  void Apply(const Row& r, const Velocity A, const Velocity B, double d) {
    vel_[r.write_a] = {A.v + r.ma_lin * d, A.w + r.ma_ang * d};
    vel_[r.write_b] = {B.v + r.mb_lin * d, B.w + r.mb_ang * d};
  }

  // Copies the caller's rows into rows_ in sweep order (see above), the
  // coloured one with a runner; group g's rows write their bodies without
  // mass to the sink world_slot + 1 + g.
  void Prepare(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies, int world_slot,
               const PgsOptions& options);
  void PrepareRow(const ConstraintRow& c, const std::vector<SolverBody>& bodies, int world_slot, int sink_slot,
                  Row* r) const;
  // Marks the rows of each block that K^+ (or K^-1) exists for; the
  // blocks' K on the runner's threads when there is one.
  void PrepareBlocks(const std::vector<PgsNormalBlock>& blocks, ParallelRunner* runner);
  // False when no block applies (see InvertNormalBlockK).
  bool BuildBlock(const PgsNormalBlock& given, Block* blk) const;
  // One projected update of a friction pair; returns its row-velocity change.
  double SolvePair(Row& r1, Row& r2);
  // One update of a row on its own bounds; returns its row-velocity change.
  double SolveRow(Row& r);
  // One update of a normal block (row by row when a point would pull).
  double SolveBlock(const Block& blk);
  // One sweep over rows_[begin, end); returns the largest row-velocity change.
  double SweepRows(int begin, int end);
  // The warm start and the sweeps: serially in rows_ order, or colour by
  // colour on the runner (pgs_stages.cpp).
  // Both end with the impulses in `rows` and on `bodies`, and the report.
  void SweepInOrder(const PgsOptions& options, std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                    SolveReport* report);
  void SweepColoured(const PgsOptions& options, std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                     SolveReport* report);

  RowSchedule schedule_;
  std::vector<int> order_, position_;  // sweep order; position_[row] = index in rows_
  std::vector<int> group_rows_;        // group g: rows_[group_rows_[g], group_rows_[g + 1])
  BlockColours colours_;               // in groups
  std::vector<double> group_worst_;    // per group, its largest change in the last sweep
  std::vector<ParallelRunner::Stage> stages_;
  std::vector<Row> rows_;
  std::vector<Block> blocks_;
  std::vector<Block> candidates_;      // per given block, valid where built_
  std::vector<char> built_;
  std::vector<double> chunk_error_;    // complementarity per chunk of rows
  std::vector<Velocity> vel_;
};

}  // namespace contactsim
