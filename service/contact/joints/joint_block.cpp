#include "service/contact/joints/joint_block.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "service/contact/joints/joint_couplings.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// rhs - J v - cfm lambda: what the row still asks, a compliant row (a
// joint's damping) counting the impulse it already carries
double RowError(const ConstraintRow& row, const std::vector<SolverBody>& bodies, double total) {
  return row.rhs - row.Velocity(bodies) - row.cfm * total;
}

void ReadVelocities(const std::vector<SolverBody>& bodies, std::vector<double>* out) {
  out->resize(6 * bodies.size());
  double* v = out->data();
  for (const SolverBody& s : bodies) {
    v = std::copy_n(s.v.data(), 3, v);
    v = std::copy_n(s.w.data(), 3, v);
  }
}

}  // namespace

void JointVelocityBlock::Build(const World& world, const std::vector<SolverBody>& bodies, double h,
                               JointSolverKind solver) {
  rows_.clear();
  blocks_.clear();
  couplings_.clear();
  solver_ = solver;
  component_.clear();
  factored_ = false;
  changed_ = false;
  built_velocities_.clear();
  if (world.joints().empty()) return;
  ReadVelocities(bodies, &built_velocities_);
  BuildJointVelocityRows(world, bodies, h, solver, &rows_, &blocks_, JointRowMode::kVelocity, &factor_);
  AppendCouplingRows(world, bodies, h, JointRowMode::kVelocity, &couplings_);
  total_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows_.size()));
  factored_ = solver == JointSolverKind::kTree && !rows_.empty() && factor_.Factor(rows_, blocks_, bodies);
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  for (const Joint& j : world.joints()) {
    const int a = world.IndexOf(j.body_a);
    const int b = j.body_b == kWorldBody ? -1 : world.IndexOf(j.body_b);
    if (a >= 0 && b >= 0) sets.Join(a, b);
  }
  component_.assign(n, -1);
  for (const Joint& j : world.joints()) {
    for (const BodyId id : {j.body_a, j.body_b}) {
      const int i = id == kWorldBody ? -1 : world.IndexOf(id);
      if (i >= 0) component_[i] = sets.Root(i);
    }
  }
}

void JointVelocityBlock::Rebuild(const World& world, const std::vector<SolverBody>& bodies, double h) {
  if (!changed_ && !built_velocities_.empty()) {
    ReadVelocities(bodies, &now_velocities_);
    if (std::memcmp(now_velocities_.data(), built_velocities_.data(), now_velocities_.size() * sizeof(double)) == 0) {
      return;
    }
  }
  const std::vector<ConstraintRow> old_rows = rows_;
  const std::vector<JointBlock> old_blocks = blocks_;
  const Eigen::VectorXd old_total = total_;
  Build(world, bodies, h, solver_);
  if (old_blocks.size() != blocks_.size()) return;
  // joint by joint, the compliant rows (damping, then the drive) in order:
  // a limit coming or going, or the friction row it removes, moves them
  for (size_t i = 0; i < blocks_.size(); ++i) {
    const JointBlock& now = blocks_[i];
    const JointBlock& before = old_blocks[i];
    if (now.joint != before.joint) return;
    int k = before.first;
    for (int r = now.first; r < now.first + now.count; ++r) {
      if (rows_[r].cfm <= 0.0) continue;
      while (k < before.first + before.count && old_rows[k].cfm <= 0.0) ++k;
      if (k == before.first + before.count) break;
      total_[r] = old_total[k++];
    }
  }
}

void JointVelocityBlock::AddDriveImpulses(std::vector<double>* impulses) const {
  contactsim::AddDriveImpulses(blocks_, std::vector<double>(total_.data(), total_.data() + total_.size()), impulses);
}

void JointVelocityBlock::AppendRows(std::vector<ConstraintRow>* out) const {
  for (size_t k = 0; k < rows_.size(); ++k) {
    out->push_back(rows_[k]);
    out->back().lambda = total_[static_cast<Eigen::Index>(k)];
  }
}

void JointVelocityBlock::ReadImpulses(const std::vector<ConstraintRow>& rows, size_t first) {
  changed_ = true;
  for (size_t k = 0; k < rows_.size(); ++k) total_[static_cast<Eigen::Index>(k)] = rows[first + k].lambda;
}

bool JointVelocityBlock::SelfContact(int a, int b) const {
  if (component_.empty() || a < 0 || b < 0) return false;
  return component_[a] >= 0 && component_[a] == component_[b];
}

double JointVelocityBlock::Solve(std::vector<SolverBody>& bodies, int max_limit_passes) {
  const int n = static_cast<int>(rows_.size());
  if (n == 0) return 0.0;
  changed_ = true;
  std::vector<char>& keep = keep_;
  keep.assign(n, 1);
  Eigen::VectorXd& b = b_;
  Eigen::VectorXd& x = x_;
  b.resize(n);
  // the first pass's right-hand side is the rows' error before the solve
  double worst = 0.0;
  for (int k = 0; k < n; ++k) {
    b[k] = RowError(rows_[k], bodies, total_[k]);
    worst = std::max(worst, std::abs(b[k]));
  }
  for (int pass = 0;; ++pass) {
    if (pass > 0) {
      for (int k = 0; k < n; ++k) b[k] = RowError(rows_[k], bodies, total_[k]);
    }
    if (pass == 0 && factored_) {
      factor_.Solve(blocks_, b, &x);  // every row kept: the system factored at Build
    } else {
      x = SolveJointRows(rows_, blocks_, bodies, b, keep, solver_);
    }
    // a limit row whose total would leave its bounds is held at the bound
    bool held = false;
    for (int k = 0; k < n; ++k) {
      const ConstraintRow& row = rows_[k];
      if (!keep[k] || !IsLimitRow(row)) continue;
      const double next = total_[k] + x[k];
      if (next >= row.lo && next <= row.hi) continue;
      const double d = std::clamp(next, row.lo, row.hi) - total_[k];
      row.Apply(d, bodies);
      total_[k] += d;
      keep[k] = 0;
      held = true;
    }
    if (held && pass + 1 < max_limit_passes) continue;
    for (int k = 0; k < n; ++k) {
      if (!keep[k]) continue;
      rows_[k].Apply(x[k], bodies);
      total_[k] += x[k];
    }
    if (!couplings_.empty()) worst = std::max(worst, SolveCouplingRows(bodies, pass == 0));
    return worst;
  }
}

double JointVelocityBlock::SolveCouplingRows(std::vector<SolverBody>& bodies, bool all_kept) {
  const int n = static_cast<int>(rows_.size());
  Eigen::VectorXd target(couplings_.size()), d_lambda, mu;
  for (size_t c = 0; c < couplings_.size(); ++c) target[c] = couplings_[c].rhs;
  const double worst = SolveCouplings(
      rows_, couplings_, target,
      [&](const Eigen::VectorXd& rhs) {
        Eigen::VectorXd x;
        if (all_kept && factored_) {
          factor_.Solve(blocks_, rhs, &x);
        } else {
          x = SolveJointRows(rows_, blocks_, bodies, rhs, keep_, solver_);
        }
        return x;
      },
      bodies, &d_lambda, &mu);
  for (int k = 0; k < n; ++k) total_[k] += d_lambda[k];
  return worst;
}

}  // namespace contactsim
