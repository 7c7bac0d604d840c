#include "service/contact/joints/joint_solver.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "service/contact/joints/joint_couplings.h"
#include "service/contact/joints/joint_dense_solver.h"
#include "service/contact/joints/joint_tree_solver.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// The rows of the kept blocks, renumbered; `source` maps back.
struct RowSubset {
  std::vector<ConstraintRow> rows;
  std::vector<JointBlock> blocks;
  std::vector<int> source;
};

// Keeps the rows with keep[k] (all when keep is empty) of the given blocks.
RowSubset Subset(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                 const std::vector<int>& block_ids, const std::vector<char>& keep) {
  RowSubset out;
  for (int id : block_ids) {
    JointBlock blk = blocks[id];
    const int first = static_cast<int>(out.rows.size());
    for (int k = blk.first; k < blk.first + blk.count; ++k) {
      if (!keep.empty() && !keep[k]) continue;
      out.rows.push_back(rows[k]);
      out.source.push_back(k);
    }
    blk.first = first;
    blk.count = static_cast<int>(out.rows.size()) - first;
    if (blk.count > 0) out.blocks.push_back(blk);
  }
  return out;
}

Eigen::VectorXd Gather(const Eigen::VectorXd& v, const std::vector<int>& source) {
  Eigen::VectorXd out(source.size());
  for (size_t i = 0; i < source.size(); ++i) out[i] = v[source[i]];
  return out;
}

std::vector<int> AllBlocks(const std::vector<JointBlock>& blocks) {
  std::vector<int> ids(blocks.size());
  for (size_t i = 0; i < ids.size(); ++i) ids[i] = static_cast<int>(i);
  return ids;
}

}  // namespace

Eigen::VectorXd SolveJointRows(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                          const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b,
                          const std::vector<char>& keep, JointSolverKind solver) {
  const RowSubset sub = Subset(rows, blocks, AllBlocks(blocks), keep);
  const Eigen::VectorXd x = SolveJointSystem(sub.rows, sub.blocks, bodies, Gather(b, sub.source), solver);
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(rows.size());
  for (size_t i = 0; i < sub.source.size(); ++i) lambda[sub.source[i]] = x[i];
  return lambda;
}

Eigen::VectorXd SolveJointSystem(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                                 const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b,
                                 JointSolverKind solver) {
  Eigen::VectorXd lambda;
  if (solver == JointSolverKind::kDense) return SolveJointsDense(rows, bodies, b);
  if (SolveJointsTree(rows, blocks, bodies, b, &lambda)) return lambda;
  // a loop somewhere: split into components, dense only where the loop is
  UnionFind sets(static_cast<int>(bodies.size()));
  auto dynamic = [&bodies](int i) { return i >= 0 && bodies[i].inv_mass > 0.0; };
  for (const JointBlock& blk : blocks) {
    if (dynamic(blk.a) && dynamic(blk.b)) sets.Join(blk.a, blk.b);
  }
  std::map<int, std::vector<int>> components;  // keyed by first body: deterministic order
  for (size_t k = 0; k < blocks.size(); ++k) {
    components[sets.Root(dynamic(blocks[k].a) ? blocks[k].a : blocks[k].b)].push_back(static_cast<int>(k));
  }
  lambda = Eigen::VectorXd::Zero(rows.size());
  for (const auto& [root, ids] : components) {
    const RowSubset sub = Subset(rows, blocks, ids, {});
    const Eigen::VectorXd sub_b = Gather(b, sub.source);
    Eigen::VectorXd x;
    if (!SolveJointsTree(sub.rows, sub.blocks, bodies, sub_b, &x)) x = SolveJointsDense(sub.rows, bodies, sub_b);
    for (size_t i = 0; i < sub.source.size(); ++i) lambda[sub.source[i]] = x[i];
  }
  return lambda;
}

namespace {

// A joint's friction row: boxed and rigid (a drive row is boxed and compliant).
bool IsFrictionRow(const ConstraintRow& row) {
  return row.cfm == 0.0 && row.lo > -ConstraintRow::kInf && row.hi < ConstraintRow::kInf;
}

// The tangent solve on every row (BuildJointVelocityRows): the geometry
// rows at J qdot = 0, the damping and drive rows at their targets. False
// when it does not apply: a friction row (held at its bound, not an
// equality) or a drive row whose impulse passes its bound.
bool SolveWholeTangent(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                       const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b, JointSolverKind solver,
                       JointTreeFactor* factor, Eigen::VectorXd* lambda) {
  const int n = static_cast<int>(rows.size());
  for (const ConstraintRow& row : rows) {
    if (IsFrictionRow(row)) return false;
  }
  Eigen::VectorXd whole = b;
  for (int k = 0; k < n; ++k) {
    if (IsJointDynamicsRow(rows[k])) whole[k] += rows[k].rhs;
  }
  if (solver == JointSolverKind::kTree && factor != nullptr && factor->Factor(rows, blocks, bodies)) {
    factor->Solve(blocks, whole, lambda);
  } else {
    *lambda = SolveJointSystem(rows, blocks, bodies, whole, solver);
  }
  for (int k = 0; k < n; ++k) {
    if (IsJointDynamicsRow(rows[k]) && ((*lambda)[k] < rows[k].lo || (*lambda)[k] > rows[k].hi)) return false;
  }
  return true;
}

}  // namespace

void BuildJointVelocityRows(const World& world, const std::vector<SolverBody>& bodies, double h,
                            JointSolverKind solver, std::vector<ConstraintRow>* rows,
                            std::vector<JointBlock>* blocks, JointRowMode mode, JointTreeFactor* factor) {
  AppendJointRows(world, bodies, h, mode, rows, blocks);
  if (rows->empty()) return;
  // the velocity the step ends with, without the velocity products:
  // qdot* + M^-1 J^T lambda0 with every geometry row (limits as equalities)
  // at J qdot = 0 and the damping and drive rows at their targets, the
  // system the velocity solve factors; where a friction row or a saturated
  // drive makes that no equality system, the geometry rows alone
  const int n = static_cast<int>(rows->size());
  Eigen::VectorXd b(n);
  for (int k = 0; k < n; ++k) b[k] = -(*rows)[k].Velocity(bodies);
  Eigen::VectorXd lambda0;
  if (!SolveWholeTangent(*rows, *blocks, bodies, b, solver, factor, &lambda0)) {
    std::vector<char> geometry(n, 1);
    for (int k = 0; k < n; ++k) geometry[k] = !IsJointDynamicsRow((*rows)[k]);
    const bool all = std::find(geometry.begin(), geometry.end(), 0) == geometry.end();
    lambda0 = all ? SolveJointSystem(*rows, *blocks, bodies, b, solver)
                  : SolveJointRows(*rows, *blocks, bodies, b, geometry, solver);
  }
  std::vector<SolverBody> tangent = bodies;
  for (int k = 0; k < n; ++k) {
    (*rows)[k].Apply(lambda0[k], tangent);
    (*rows)[k].lambda = std::clamp(lambda0[k], (*rows)[k].lo, (*rows)[k].hi);
  }
  // the velocity products there, for the equality rows (the first rows of
  // each block); a limit, damping or drive row keeps its target
  SetJointVelocityProducts(world, tangent, h, *blocks, rows);
}

namespace {

// The active-set solve of the rows on `bodies` (see ApplyJointImpulses):
// applies the impulses and leaves them in the rows' lambda.
JointStats SolveActiveSet(std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                          std::vector<SolverBody>& bodies, JointSolverKind solver, int max_passes,
                          const std::vector<CouplingRow>& couplings = {}) {
  JointStats stats;
  const int n = static_cast<int>(rows.size());
  Eigen::VectorXd b(n);
  for (int k = 0; k < n; ++k) b[k] = rows[k].rhs - rows[k].Velocity(bodies);
  // active set over the bounded rows (limits, friction): a row whose
  // impulse leaves its bounds is held at the bound it passed (a limit at 0,
  // friction at +-f h) and the others solved again
  std::vector<char> keep(n, 1);
  Eigen::VectorXd lambda;
  for (int pass = 0;; ++pass) {
    lambda = SolveJointRows(rows, blocks, bodies, b, keep, solver);
    ++stats.limit_passes;
    bool dropped = false, moved = false;
    for (int k = 0; k < n; ++k) {
      if (keep[k] && IsLimitRow(rows[k]) && (lambda[k] < rows[k].lo || lambda[k] > rows[k].hi)) {
        keep[k] = 0;
        dropped = true;
        const double bound = std::clamp(lambda[k], rows[k].lo, rows[k].hi);
        rows[k].lambda = bound;
        if (bound == 0.0) continue;
        rows[k].Apply(bound, bodies);
        moved = true;
      }
    }
    if (!dropped || pass + 1 >= max_passes) break;
    if (moved) {
      for (int k = 0; k < n; ++k) b[k] = rows[k].rhs - rows[k].Velocity(bodies);
    }
  }
  for (int k = 0; k < n; ++k) {
    if (!keep[k]) continue;
    rows[k].lambda = std::clamp(lambda[k], rows[k].lo, rows[k].hi);
    rows[k].Apply(rows[k].lambda, bodies);
    ++stats.rows;
  }
  if (couplings.empty()) return stats;
  // the mimics' rows, with the active set the joints chose (joint_couplings.h)
  Eigen::VectorXd target(couplings.size()), d_lambda, mu;
  for (size_t c = 0; c < couplings.size(); ++c) target[c] = couplings[c].rhs;
  SolveCouplings(rows, couplings, target,
                 [&](const Eigen::VectorXd& rhs) { return SolveJointRows(rows, blocks, bodies, rhs, keep, solver); },
                 bodies, &d_lambda, &mu);
  for (int k = 0; k < n; ++k) rows[k].lambda += d_lambda[k];
  stats.rows += static_cast<int>(couplings.size());
  return stats;
}

// The mimics' share of a Newton step of the projection: the displacement
// in `bodies` (v, w) then also takes each coupling error C_c to 0 to first
// order, keeping the joint rows' step.
void ProjectCouplings(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                      const std::vector<CouplingRow>& couplings, JointSolverKind solver,
                      std::vector<SolverBody>& bodies) {
  Eigen::VectorXd target(couplings.size()), d_lambda, mu;
  for (size_t c = 0; c < couplings.size(); ++c) target[c] = -couplings[c].error;
  SolveCouplings(rows, couplings, target,
                 [&](const Eigen::VectorXd& rhs) { return SolveJointSystem(rows, blocks, bodies, rhs, solver); },
                 bodies, &d_lambda, &mu);
}

}  // namespace

void GuessJointImpulses(const std::vector<SolverBody>& bodies, JointSolverKind solver,
                        std::vector<ConstraintRow>* rows, const std::vector<JointBlock>& blocks) {
  std::vector<SolverBody> scratch = bodies;
  SolveActiveSet(*rows, blocks, scratch, solver, JointSolveOptions().max_limit_passes);
}

JointStats ApplyJointImpulses(const World& world, double h, std::vector<SolverBody>& bodies,
                              const JointSolveOptions& options, std::vector<double>* drive_impulses) {
  std::vector<ConstraintRow> rows;
  std::vector<JointBlock> blocks;
  BuildJointVelocityRows(world, bodies, h, options.solver, &rows, &blocks,
                         options.joint_dynamics ? JointRowMode::kVelocity : JointRowMode::kVelocityGeometry);
  if (rows.empty()) return {};
  std::vector<CouplingRow> couplings;
  AppendCouplingRows(world, bodies, h, JointRowMode::kVelocity, &couplings);
  const JointStats stats =
      SolveActiveSet(rows, blocks, bodies, options.solver, options.max_limit_passes, couplings);
  if (drive_impulses != nullptr) {
    std::vector<double> lambda(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) lambda[k] = rows[k].lambda;
    AddDriveImpulses(blocks, lambda, drive_impulses);
  }
  return stats;
}

JointStats SolveJointVelocities(World& world, double h, const JointSolveOptions& options) {
  if (world.joints().empty()) return {};
  std::vector<SolverBody> bodies;
  LoadSolverBodies(world, &bodies);
  std::vector<double> drive_impulses;
  const JointStats stats = ApplyJointImpulses(world, h, bodies, options, &drive_impulses);
  StoreSolverBodies(bodies, world);
  AddDriveEfforts(drive_impulses, world.dt, world);
  return stats;
}

namespace {

// A Newton step's factorisation kept for a chord step of the projection
// (joint_solver.h): it serves the next iteration when the last step cut the
// largest error by kChordCut at least (the factored Jacobians are still
// close) and that error is within kChordReach of the tolerance (one chord
// step, which cuts it by about kChordCut again, then ends the projection;
// further from it, a fresh Newton step converges in fewer iterations).
constexpr double kChordCut = 1e-3;
constexpr double kChordReach = 1e3;

bool ChordApplies(double error, double last_error, double tolerance) {
  return last_error > 0.0 && error <= kChordCut * last_error && error <= kChordReach * tolerance;
}

class ProjectionFactor {
 public:
  // delta solving (J M^-1 J^T + R) delta = b at the rows' poses, or, with
  // `chord` and a factorisation of the same blocks held, with the matrix
  // factored at an earlier iteration's poses.
  Eigen::VectorXd Solve(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                        const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b, bool chord,
                        JointSolverKind solver) {
    Eigen::VectorXd delta;
    if (chord && held_ && SameShape(blocks)) {
      factor_.Solve(blocks, b, &delta);
      return delta;
    }
    // at poses the projection has just moved, a system never repeats the
    // last one: no reuse key (JointTreeFactor::Factor)
    held_ = solver == JointSolverKind::kTree && factor_.Factor(rows, blocks, bodies, /*reuse=*/false);
    if (!held_) return SolveJointSystem(rows, blocks, bodies, b, solver);
    shape_.assign(blocks.begin(), blocks.end());
    factor_.Solve(blocks, b, &delta);
    return delta;
  }
  // Forgets the factors: nothing of one projection reaches the next.
  void Reset() { held_ = false; }

 private:
  bool SameShape(const std::vector<JointBlock>& blocks) const {
    if (blocks.size() != shape_.size()) return false;
    for (size_t i = 0; i < blocks.size(); ++i) {
      const JointBlock& x = blocks[i];
      const JointBlock& y = shape_[i];
      if (x.first != y.first || x.count != y.count || x.a != y.a || x.b != y.b) return false;
    }
    return true;
  }

  // one per thread, kept so that its nodes' storage serves the next
  // projection (JointTreeFactor); its factors serve one projection only
  JointTreeFactor factor_;
  std::vector<JointBlock> shape_;  // the blocks factor_ was factored with
  bool held_ = false;
};

}  // namespace

JointStats ProjectJointPositions(World& world, const JointSolveOptions& options) {
  JointStats stats;
  if (world.joints().empty()) return stats;
  thread_local ProjectionFactor factor;
  factor.Reset();
  // kept per thread so that their storage serves the next projection
  thread_local std::vector<SolverBody> bodies;
  thread_local std::vector<ConstraintRow> rows;
  thread_local std::vector<JointBlock> blocks;
  thread_local std::vector<double> errors;
  thread_local std::vector<CouplingRow> couplings;
  double last_error = 0.0;
  // Position rows read the solver bodies' indices and inverse masses only
  // (joint_rows.h), which a displacement leaves alone: the bodies are
  // loaded again at the new poses (their world inertias) only for a solve,
  // not for the check that ends the projection. The first check builds
  // the rows with their errors (a step's drift nearly always asks for an
  // iteration); a check after a displacement, which usually ends the
  // projection, takes the errors alone (AppendJointErrors: no Jacobians).
  LoadSolverBodies(world, &bodies);
  bool displaced = false;
  for (;;) {
    rows.clear();
    blocks.clear();
    errors.clear();
    couplings.clear();
    if (displaced) {
      AppendJointErrors(world, bodies, &errors);
    } else {
      AppendJointRows(world, bodies, 0.0, JointRowMode::kPosition, &rows, &blocks, &errors);
    }
    AppendCouplingRows(world, bodies, 0.0, JointRowMode::kPosition, &couplings);
    stats.max_error = 0.0;
    for (double e : errors) stats.max_error = std::max(stats.max_error, std::abs(e));
    for (const CouplingRow& c : couplings) stats.max_error = std::max(stats.max_error, std::abs(c.error));
    if (stats.max_error <= options.projection_tolerance ||
        stats.projection_iterations >= options.max_projection_iterations) {
      break;
    }
    ++stats.projection_iterations;
    if (displaced) {
      LoadSolverBodies(world, &bodies);
      AppendJointRows(world, bodies, 0.0, JointRowMode::kPosition, &rows, &blocks);
    }
    const Eigen::VectorXd b = -Eigen::Map<const Eigen::VectorXd>(errors.data(), errors.size());
    // a mimic's coupling solve factors afresh (SolveJointSystem): no chord there
    const bool chord =
        options.chord_steps && couplings.empty() &&
        ChordApplies(stats.max_error, last_error, options.projection_tolerance);
    const Eigen::VectorXd delta = factor.Solve(rows, blocks, bodies, b, chord, options.solver);
    last_error = stats.max_error;
    // the solver bodies carry the displacement: v = M^-1 J^T delta (m),
    // w = I^-1 J^T delta (rad)
    for (SolverBody& s : bodies) s.v.setZero(), s.w.setZero();
    for (size_t k = 0; k < rows.size(); ++k) rows[k].Apply(delta[k], bodies);
    if (!couplings.empty()) ProjectCouplings(rows, blocks, couplings, options.solver, bodies);
    DisplaceBodies(bodies, world);
    displaced = true;
  }
  return stats;
}

}  // namespace contactsim
