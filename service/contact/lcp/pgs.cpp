#include "service/contact/lcp/pgs.h"

#include <algorithm>
#include <cmath>

#include "service/contact/lcp/friction_disk.h"
#include "service/contact/lcp/row_complementarity.h"

namespace contactsim {

namespace {

// groups (of rows) and normal blocks a thread prepares at a time
constexpr int kPgsPrepareGrain = 16;
constexpr int kPgsBlockGrain = 64;
// rows a thread inverts the sweep order of at a time (a store each)
constexpr int kPgsRowGrain = 2048;

}  // namespace

void PgsSolver::PrepareRow(const ConstraintRow& c, const std::vector<SolverBody>& bodies, int world_slot,
                           int sink_slot, Row* out) const {
  // flat copy with M^-1 J^T; bodies without mass get zero blocks (their
  // velocity, e.g. a kinematic body's, still enters J v)
  Row& r = *out;
  r.a = c.a >= 0 ? c.a : world_slot;
  r.b = c.b >= 0 ? c.b : world_slot;
  r.write_a = c.a >= 0 && bodies[c.a].inv_mass > 0.0 ? c.a : sink_slot;
  r.write_b = c.b >= 0 && bodies[c.b].inv_mass > 0.0 ? c.b : sink_slot;
  r.ja_lin = c.a >= 0 ? c.lin_a : Vec3::Zero();
  r.ja_ang = c.a >= 0 ? c.ang_a : Vec3::Zero();
  r.jb_lin = c.b >= 0 ? c.lin_b : Vec3::Zero();
  r.jb_ang = c.b >= 0 ? c.ang_b : Vec3::Zero();
  const SolverBody* A = c.a >= 0 ? &bodies[c.a] : nullptr;
  const SolverBody* B = c.b >= 0 ? &bodies[c.b] : nullptr;
  r.ma_lin = A ? Vec3(A->inv_mass * r.ja_lin) : Vec3::Zero();
  r.ma_ang = A ? Vec3(A->inv_inertia * r.ja_ang) : Vec3::Zero();
  r.mb_lin = B ? Vec3(B->inv_mass * r.jb_lin) : Vec3::Zero();
  r.mb_ang = B ? Vec3(B->inv_inertia * r.jb_ang) : Vec3::Zero();
  // J M^-1 J^T from the M^-1 J^T above, the same sums as ConstraintRow::Diagonal
  double diag = 0.0;
  if (A) diag += A->inv_mass * r.ja_lin.squaredNorm() + r.ja_ang.dot(r.ma_ang);
  if (B) diag += B->inv_mass * r.jb_lin.squaredNorm() + r.jb_ang.dot(r.mb_ang);
  r.diag = diag;
  r.cfm = c.cfm;
  r.inv_diag = r.diag + r.cfm > 0.0 ? 1.0 / (r.diag + r.cfm) : 0.0;
  r.rhs = c.rhs;
  r.lo = c.lo;
  r.hi = c.hi;
  r.mu = c.mu;
  r.lambda = c.lambda;
}

void PgsSolver::Prepare(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                        int world_slot, const PgsOptions& options) {
  ParallelRunner* runner = options.runner;
  if (runner != nullptr) {
    const int ordered = options.ordered_from >= 0 ? options.ordered_from : static_cast<int>(rows.size());
    schedule_.Colour(rows, bodies, ordered, &order_, &group_rows_, &colours_, runner);
  } else {
    schedule_.Order(rows, bodies, &order_);
    group_rows_ = {0, static_cast<int>(rows.size())};
  }
  position_.resize(rows.size());
  // a permutation's inverse: each slot written once
  const auto invert = [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) position_[order_[k]] = k;
  };
  if (runner != nullptr) {
    runner->For(static_cast<int>(order_.size()), kPgsRowGrain, invert);
  } else {
    invert(0, static_cast<int>(order_.size()), 0);
  }
  const int groups = static_cast<int>(group_rows_.size()) - 1;
  vel_.resize(world_slot + 1 + groups);
  for (int g = 0; g < groups; ++g) vel_[world_slot + 1 + g] = {Vec3::Zero(), Vec3::Zero()};
  rows_.resize(rows.size());
  const auto prepare = [&](int begin, int end, int) {
    for (int g = begin; g < end; ++g) {
      for (int k = group_rows_[g]; k < group_rows_[g + 1]; ++k) {
        const int source = order_[k];
        Row& r = rows_[k];
        PrepareRow(rows[source], bodies, world_slot, world_slot + 1 + g, &r);
        r.normal_row = rows[source].normal_row >= 0 ? position_[rows[source].normal_row] : -1;
        r.second = IsFrictionPairLead(rows, source) ? position_[source + 1] : -1;
        r.in_pair = IsFrictionPairSecond(rows, source);
        r.block = -1;
        r.in_block = false;
        r.source = source;
      }
    }
  };
  if (runner != nullptr) {
    runner->For(groups, kPgsPrepareGrain, prepare);
  } else {
    prepare(0, groups, 0);
  }
}

bool PgsSolver::BuildBlock(const PgsNormalBlock& given, Block* out) const {
  if (given.count < 2) return false;
  Block& blk = *out;
  blk.count = given.count;
  for (int i = 0; i < given.count; ++i) blk.rows[i] = position_[given.rows[i]];
  std::sort(blk.rows, blk.rows + blk.count);
  const Row& r0 = rows_[blk.rows[0]];
  // B's side unless B is the world (whose J is zero): n, and r x n to
  // place each point in the face's plane, all from one side
  const bool b_side = r0.jb_lin.squaredNorm() > 0.0;
  const Vec3 n = b_side ? r0.jb_lin : Vec3(-r0.ja_lin);
  Eigen::Matrix4d k = Eigen::Matrix4d::Zero();
  Vec3 plane[kMaxNormalBlock];
  bool one_normal = true;
  for (int i = 0; i < blk.count; ++i) {
    const Row& ri = rows_[blk.rows[i]];
    one_normal = one_normal && ri.a == r0.a && ri.b == r0.b && ri.ja_lin == r0.ja_lin && ri.jb_lin == r0.jb_lin;
    plane[i] = b_side ? ri.jb_ang : Vec3(-ri.ja_ang);
    // the lower triangle: the inverse reads no other (small_spd_inverse.h)
    for (int j = 0; j <= i; ++j) {
      const Row& rj = rows_[blk.rows[j]];
      k(i, j) = ri.ja_lin.dot(rj.ma_lin) + ri.ja_ang.dot(rj.ma_ang) + ri.jb_lin.dot(rj.mb_lin) +
                ri.jb_ang.dot(rj.mb_ang);
    }
  }
  // the face's tangents place a four-point block's points (FaceNullVector)
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();
  if (blk.count == kMaxNormalBlock) PerpendicularBasis(n, &t1, &t2);
  return one_normal && InvertNormalBlockK(k, blk.count, plane, t1, t2, &blk.inv_k);
}

void PgsSolver::PrepareBlocks(const std::vector<PgsNormalBlock>& blocks, ParallelRunner* runner) {
  const int n = static_cast<int>(blocks.size());
  candidates_.resize(blocks.size());
  built_.resize(blocks.size());
  const auto build = [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) built_[i] = BuildBlock(blocks[i], &candidates_[i]);
  };
  if (runner != nullptr) {
    runner->For(n, kPgsBlockGrain, build);
  } else {
    build(0, n, 0);
  }
  for (int i = 0; i < n; ++i) {
    if (!built_[i]) continue;
    const Block& blk = candidates_[i];
    rows_[blk.rows[0]].block = static_cast<int>(blocks_.size());
    for (int j = 1; j < blk.count; ++j) rows_[blk.rows[j]].in_block = true;
    blocks_.push_back(blk);
  }
}

double PgsSolver::SolvePair(Row& r1, Row& r2) {
  // both rows act on the same two bodies (one contact)
  const Velocity A = vel_[r1.a];
  const Velocity B = vel_[r1.b];
  const double jv1 = r1.ja_lin.dot(A.v) + r1.ja_ang.dot(A.w) + r1.jb_lin.dot(B.v) + r1.jb_ang.dot(B.w);
  const double jv2 = r2.ja_lin.dot(A.v) + r2.ja_ang.dot(A.w) + r2.jb_lin.dot(B.v) + r2.jb_ang.dot(B.w);
  const double trace = r1.diag + r2.diag;
  const double eta = trace > 0.0 ? 2.0 / trace : 0.0;
  double l1 = r1.lambda + eta * (r1.rhs - jv1);
  double l2 = r2.lambda + eta * (r2.rhs - jv2);
  ProjectOntoDisk(std::max(0.0, r1.mu * rows_[r1.normal_row].lambda), &l1, &l2);
  const double d1 = l1 - r1.lambda, d2 = l2 - r2.lambda;
  r1.lambda = l1;
  r2.lambda = l2;
  vel_[r1.write_a] = {A.v + r1.ma_lin * d1 + r2.ma_lin * d2, A.w + r1.ma_ang * d1 + r2.ma_ang * d2};
  vel_[r1.write_b] = {B.v + r1.mb_lin * d1 + r2.mb_lin * d2, B.w + r1.mb_ang * d1 + r2.mb_ang * d2};
  return std::max(std::abs(d1) * r1.diag, std::abs(d2) * r2.diag);
}

double PgsSolver::SolveRow(Row& r) {
  double lo = r.lo, hi = r.hi;
  if (r.normal_row >= 0) {
    hi = r.mu * rows_[r.normal_row].lambda;
    lo = -hi;
  }
  const Velocity A = vel_[r.a];
  const Velocity B = vel_[r.b];
  const double jv = r.ja_lin.dot(A.v) + r.ja_ang.dot(A.w) + r.jb_lin.dot(B.v) + r.jb_ang.dot(B.w);
  // a compliant row aims at J v + cfm lambda = rhs (constraint_row.h)
  const double next = std::clamp(r.lambda + (r.rhs - jv - r.cfm * r.lambda) * r.inv_diag, lo, hi);
  const double d = next - r.lambda;
  r.lambda = next;
  Apply(r, A, B, d);
  return std::abs(d) * r.diag;
}

double PgsSolver::SolveBlock(const Block& blk) {
  // every row of the block acts on the same two bodies
  const Row& r0 = rows_[blk.rows[0]];
  const Velocity A = vel_[r0.a];
  const Velocity B = vel_[r0.b];
  Eigen::Vector4d error = Eigen::Vector4d::Zero();
  for (int i = 0; i < blk.count; ++i) {
    const Row& r = rows_[blk.rows[i]];
    error[i] = r.rhs - (r.ja_lin.dot(A.v) + r.ja_ang.dot(A.w) + r.jb_lin.dot(B.v) + r.jb_ang.dot(B.w));
  }
  const Eigen::Vector4d step = blk.inv_k * error;
  bool keep = true;
  for (int i = 0; i < blk.count; ++i) keep = keep && rows_[blk.rows[i]].lambda + step[i] >= 0.0;
  double worst = 0.0;
  if (!keep) {
    for (int i = 0; i < blk.count; ++i) worst = std::max(worst, SolveRow(rows_[blk.rows[i]]));
    return worst;
  }
  // one write of each body's velocity for the whole block
  Velocity a = A, b = B;
  for (int i = 0; i < blk.count; ++i) {
    Row& r = rows_[blk.rows[i]];
    r.lambda += step[i];
    a.v += r.ma_lin * step[i];
    a.w += r.ma_ang * step[i];
    b.v += r.mb_lin * step[i];
    b.w += r.mb_ang * step[i];
    worst = std::max(worst, std::abs(step[i]) * r.diag);
  }
  vel_[r0.write_a] = a;
  vel_[r0.write_b] = b;
  return worst;
}

double PgsSolver::SweepRows(int begin, int end) {
  double worst = 0.0;
  for (int k = begin; k < end; ++k) {
    Row& r = rows_[k];
    if (r.in_pair || r.in_block) continue;  // updated with its pair's or block's first row
    if (r.second >= 0) {
      worst = std::max(worst, SolvePair(r, rows_[r.second]));
    } else if (r.block >= 0) {
      worst = std::max(worst, SolveBlock(blocks_[r.block]));
    } else {
      worst = std::max(worst, SolveRow(r));
    }
  }
  return worst;
}

void PgsSolver::SweepInOrder(const PgsOptions& options, std::vector<ConstraintRow>& rows,
                             std::vector<SolverBody>& bodies, SolveReport* report) {
  for (const Row& r : rows_) {
    if (r.lambda != 0.0) Apply(r, vel_[r.a], vel_[r.b], r.lambda);
  }
  for (int it = 0; it < options.iterations; ++it) {
    const double worst = SweepRows(0, static_cast<int>(rows_.size()));
    report->iterations = it + 1;
    report->residual = worst;
    if (worst < options.tolerance && it + 1 >= options.min_iterations) {
      report->converged = true;
      break;
    }
  }
  // the impulses go to the bodies through ConstraintRow::Apply, so dP and dL sum
  for (const Row& r : rows_) rows[r.source].lambda = r.lambda;
  for (ConstraintRow& row : rows) row.Apply(row.lambda, bodies);
  if (options.measure_complementarity) report->complementarity = ComplementarityError(rows, bodies);
}

SolveReport PgsSolver::Solve(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                             const PgsOptions& options) {
  SolveReport report;
  const int world_slot = static_cast<int>(bodies.size());
  vel_.resize(bodies.size() + 1);
  for (size_t i = 0; i < bodies.size(); ++i) vel_[i] = {bodies[i].v, bodies[i].w};
  vel_[world_slot] = {Vec3::Zero(), Vec3::Zero()};
  Prepare(rows, bodies, world_slot, options);
  blocks_.clear();
  if (options.normal_blocks != nullptr) PrepareBlocks(*options.normal_blocks, options.runner);
  if (options.runner != nullptr) {
    SweepColoured(options, rows, bodies, &report);
  } else {
    SweepInOrder(options, rows, bodies, &report);
  }
  return report;
}

}  // namespace contactsim
