#include "service/contact/subspace_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "service/contact/min_norm_solve.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// m/s: a held row rejoins the free set when the solution makes it approach
// (or pull) faster than this; well above the solve's round-off
constexpr double kJoinTolerance = 1e-9;

bool Dynamic(int i, const std::vector<SolverBody>& s) { return i >= 0 && s[i].inv_mass > 0.0; }

// J_p M^-1 J_q^T: the entry of A = J M^-1 J^T coupling rows p and q through
// the bodies they share.
double Coupling(const ConstraintRow& p, const ConstraintRow& q, const std::vector<SolverBody>& s) {
  auto part = [&s](int body, const Vec3& lin_p, const Vec3& ang_p, const Vec3& lin_q, const Vec3& ang_q) {
    return s[body].inv_mass * lin_p.dot(lin_q) + ang_p.dot(s[body].inv_inertia * ang_q);
  };
  double sum = 0.0;
  if (Dynamic(p.a, s)) {
    if (p.a == q.a) sum += part(p.a, p.lin_a, p.ang_a, q.lin_a, q.ang_a);
    if (p.a == q.b) sum += part(p.a, p.lin_a, p.ang_a, q.lin_b, q.ang_b);
  }
  if (Dynamic(p.b, s)) {
    if (p.b == q.a) sum += part(p.b, p.lin_b, p.ang_b, q.lin_a, q.ang_a);
    if (p.b == q.b) sum += part(p.b, p.lin_b, p.ang_b, q.lin_b, q.ang_b);
  }
  return sum;
}

// The m x m matrix of `entries` in compressed column form. No two entries
// share a place, and within a column they come in ascending row order, so
// this is the matrix setFromTriplets builds from them, value for value and
// in the same order, without its transposed copy, duplicate search and
// allocations.
void FillColumns(int m, const std::vector<Eigen::Triplet<double>>& entries, std::vector<int>* cursor,
                 Eigen::SparseMatrix<double>* a) {
  a->resize(m, m);  // compressed, column starts zeroed
  a->resizeNonZeros(static_cast<Eigen::Index>(entries.size()));
  int* start = a->outerIndexPtr();
  for (const Eigen::Triplet<double>& e : entries) ++start[e.col() + 1];
  for (int c = 0; c < m; ++c) start[c + 1] += start[c];
  cursor->assign(start, start + m);
  int* inner = a->innerIndexPtr();
  double* value = a->valuePtr();
  for (const Eigen::Triplet<double>& e : entries) {
    const int at = (*cursor)[e.col()]++;
    inner[at] = e.row();
    value[at] = e.value();
  }
}

// Sets a row's impulse to `value` and gives the bodies the difference.
void SetImpulse(ConstraintRow& row, double value, std::vector<SolverBody>& bodies) {
  row.Apply(value - row.lambda, bodies);
  row.lambda = value;
}

}  // namespace

bool SubspaceSolver::MassRatioReached(const std::vector<SolverBody>& bodies, double ratio) {
  if (ratio <= 0.0) return false;
  double lightest = 0.0, heaviest = std::numeric_limits<double>::infinity();  // inverse masses
  for (const SolverBody& b : bodies) {
    if (b.inv_mass <= 0.0) continue;
    lightest = std::max(lightest, b.inv_mass);
    heaviest = std::min(heaviest, b.inv_mass);
  }
  return lightest >= ratio * heaviest;
}

SubspaceReport SubspaceSolver::Solve(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                                     const SubspaceOptions& options) {
  SubspaceReport report;
  release_friction_ = options.release_friction;
  const std::vector<char>* always = options.always;
  if (rows.empty() || (always == nullptr && !MassRatioReached(bodies, options.mass_ratio))) return report;
  // components of dynamic bodies joined by rows, and their mass range
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  for (const ConstraintRow& r : rows) {
    if (Dynamic(r.a, bodies) && Dynamic(r.b, bodies)) sets.Join(r.a, r.b);
  }
  std::vector<double> lightest(n, 0.0), heaviest(n, std::numeric_limits<double>::infinity());  // inverse masses
  for (int i = 0; i < n; ++i) {
    if (!Dynamic(i, bodies)) continue;
    const int root = sets.Root(i);
    lightest[root] = std::max(lightest[root], bodies[i].inv_mass);
    heaviest[root] = std::min(heaviest[root], bodies[i].inv_mass);
  }
  // the components that need the solve: a mass ratio, or a marked body
  std::vector<char> wanted(n, 0);
  for (int i = 0; i < n; ++i) {
    if (!Dynamic(i, bodies)) continue;
    const int root = sets.Root(i);
    const bool ratio = options.mass_ratio > 0.0 && lightest[root] >= options.mass_ratio * heaviest[root];
    if (ratio || (always != nullptr && (*always)[i])) wanted[root] = 1;
  }
  // the rows of each component that needs the solve, in row order
  root_of_row_.assign(rows.size(), -1);
  std::vector<int> count(n, 0);
  for (size_t k = 0; k < rows.size(); ++k) {
    const ConstraintRow& r = rows[k];
    const int body = Dynamic(r.a, bodies) ? r.a : Dynamic(r.b, bodies) ? r.b : -1;
    if (body < 0) continue;
    const int root = sets.Root(body);
    if (!wanted[root]) continue;
    root_of_row_[k] = root;
    ++count[root];
  }
  // each component's rows in row order, bucketed in one pass (a falling
  // crowd has as many components as bodies)
  std::vector<int> start(n + 1, 0);
  for (int root = 0; root < n; ++root) start[root + 1] = start[root] + count[root];
  std::vector<int> by_component(start[n]), cursor(start.begin(), start.end() - 1);
  for (size_t k = 0; k < rows.size(); ++k) {
    if (root_of_row_[k] >= 0) by_component[cursor[root_of_row_[k]]++] = static_cast<int>(k);
  }
  std::vector<int> members;
  for (int root = 0; root < n; ++root) {
    if (count[root] == 0 || count[root] > options.max_rows) continue;
    members.assign(by_component.begin() + start[root], by_component.begin() + start[root + 1]);
    const double start = options.energy_guard ? KineticEnergy(members, rows, bodies, true) : 0.0;
    report.passes += SolveComponent(members, rows, bodies, options.passes, options.start_free);
    if (options.energy_guard && GainedEnergy(members, rows, bodies, start)) {
      for (int k : members) SetImpulse(rows[k], 0.0, bodies);
      report.passes += SolveComponent(members, rows, bodies, options.restart_passes, true);
      ++report.restarts;
    }
    ++report.components;
    report.rows += static_cast<int>(members.size());
  }
  return report;
}

double SubspaceSolver::KineticEnergy(const std::vector<int>& members, const std::vector<ConstraintRow>& rows,
                                     const std::vector<SolverBody>& bodies, bool before) {
  counted_.resize(bodies.size(), 0);
  ++energy_calls_;
  double energy = 0.0;
  for (int k : members) {
    for (int i : {rows[k].a, rows[k].b}) {
      if (!Dynamic(i, bodies) || counted_[i] == energy_calls_) continue;
      counted_[i] = energy_calls_;
      const SolverBody& s = bodies[i];
      const Vec3 v = before ? Vec3(s.v - s.inv_mass * s.dP) : s.v;
      const Vec3 w = before ? Vec3(s.w - s.inv_inertia * s.dL) : s.w;
      energy += 0.5 * (v.squaredNorm() / s.inv_mass + w.dot(s.inv_inertia.inverse() * w));
    }
  }
  return energy;
}

bool SubspaceSolver::GainedEnergy(const std::vector<int>& members, const std::vector<ConstraintRow>& rows,
                                  const std::vector<SolverBody>& bodies, double start) {
  double allowed = start * (1.0 + 1e-3) + 1e-12;
  for (int k : members) allowed += std::max(0.0, rows[k].lambda * rows[k].rhs);
  return KineticEnergy(members, rows, bodies, false) > allowed;
}

void SubspaceSolver::BuildCoupling(const std::vector<int>& members, const std::vector<ConstraintRow>& rows,
                                   const std::vector<SolverBody>& bodies) {
  // A's entries are nonzero only for rows that share a dynamic body: list
  // each body's rows, then couple each row with the rows on its bodies once
  const int m = static_cast<int>(members.size());
  body_rows_.resize(bodies.size());
  for (int i = 0; i < m; ++i) {
    const ConstraintRow& r = rows[members[i]];
    if (Dynamic(r.a, bodies)) body_rows_[r.a].clear();
    if (Dynamic(r.b, bodies)) body_rows_[r.b].clear();
  }
  for (int i = 0; i < m; ++i) {
    const ConstraintRow& r = rows[members[i]];
    if (Dynamic(r.a, bodies)) body_rows_[r.a].push_back(i);
    if (Dynamic(r.b, bodies) && r.b != r.a) body_rows_[r.b].push_back(i);
  }
  triplets_.clear();
  seen_.assign(m, -1);
  for (int i = 0; i < m; ++i) {
    const ConstraintRow& r = rows[members[i]];
    for (int body : {r.a, r.b}) {
      if (!Dynamic(body, bodies)) continue;
      for (int j : body_rows_[body]) {
        if (seen_[j] == i) continue;
        seen_[j] = i;
        triplets_.emplace_back(i, j, Coupling(r, rows[members[j]], bodies) + (i == j ? r.cfm : 0.0));
      }
    }
  }
  FillColumns(m, triplets_, &cursor_, &A_);  // the rows i come in ascending order
  diag_ = A_.diagonal();
}

SubspaceSolver::Step SubspaceSolver::LongestStep(const std::vector<int>& members, const std::vector<int>& free_rows,
                                                 const Eigen::VectorXd& dl,
                                                 const std::vector<ConstraintRow>& rows) const {
  Step step;
  // the step at which lambda + alpha slope reaches `room` (>= 0 now) away;
  // the first row to stop it is held (one row a pass: holding every row
  // already at a bound at once failed the same bridges as clamping)
  auto limit = [&step](double room, double slope, int i) {
    if (slope <= 0.0) return;
    const double alpha = std::max(0.0, room) / slope;
    if (alpha < step.alpha) step.alpha = alpha, step.blocking = i;
  };
  for (int i = 0; i < static_cast<int>(free_rows.size()); ++i) {
    const ConstraintRow& r = rows[members[free_rows[i]]];
    if (r.normal_row < 0) {
      limit(r.hi - r.lambda, dl(i), i);
      limit(r.lambda - r.lo, -dl(i), i);
      continue;
    }
    // |lambda_t + alpha dl_t| <= mu (lambda_n + alpha dl_n), dl_n 0 when
    // the normal row is held
    const int normal = member_of_[r.normal_row];
    const int at = normal >= 0 ? position_[normal] : -1;
    const double dn = at >= 0 ? dl(at) : 0.0;
    const double bound = r.mu * rows[r.normal_row].lambda;
    limit(bound - r.lambda, dl(i) - r.mu * dn, i);
    limit(bound + r.lambda, -dl(i) - r.mu * dn, i);
  }
  return step;
}

bool SubspaceSolver::ClampPastBounds(const std::vector<int>& members, const std::vector<int>& free_rows,
                                     const Eigen::VectorXd& dl, std::vector<char>& held,
                                     std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies) {
  // a sticking friction row's bound is mu times its normal row's new
  // impulse (a row leaving it slides: held at the bound)
  bool clamped = false;
  for (int i = 0; i < static_cast<int>(free_rows.size()); ++i) {
    ConstraintRow& r = rows[members[free_rows[i]]];
    const double next = r.lambda + dl(i);
    double lo = r.lo, hi = r.hi;
    if (r.normal_row >= 0) {
      const int normal = member_of_[r.normal_row];
      const int at = normal >= 0 ? position_[normal] : -1;
      hi = r.mu * std::max(0.0, rows[r.normal_row].lambda + (at >= 0 ? dl(at) : 0.0));
      lo = -hi;
    }
    if (next < lo || next > hi) {
      SetImpulse(r, next < lo ? lo : hi, bodies);
      held[free_rows[i]] = true;
      clamped = true;
    }
  }
  if (clamped) return true;
  for (int i = 0; i < static_cast<int>(free_rows.size()); ++i) {
    ConstraintRow& r = rows[members[free_rows[i]]];
    SetImpulse(r, r.lambda + dl(i), bodies);
  }
  return false;
}

bool SubspaceSolver::StepWithinBounds(const std::vector<int>& members, const std::vector<int>& free_rows,
                                      const Eigen::VectorXd& dl, std::vector<char>& held,
                                      std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies) {
  const Step step = LongestStep(members, free_rows, dl, rows);
  for (int i = 0; i < static_cast<int>(free_rows.size()); ++i) {
    ConstraintRow& r = rows[members[free_rows[i]]];
    SetImpulse(r, r.lambda + step.alpha * dl(i), bodies);
  }
  if (step.blocking < 0) return false;
  const int i = free_rows[step.blocking];
  held[i] = true;
  ConstraintRow& r = rows[members[i]];
  double lo = r.lo, hi = r.hi;
  if (r.normal_row >= 0) hi = r.mu * std::max(0.0, rows[r.normal_row].lambda), lo = -hi;
  SetImpulse(r, std::clamp(r.lambda, lo, hi), bodies);
  return true;
}

// A friction row held at its bound keeps the bound of the pass that
// clamped it, mu times its normal's impulse then; a later pass may lower
// that impulse (a tentative answer along a nearly singular direction can
// ask for a huge normal impulse and have it clamped away next pass), so
// held friction is brought back inside mu times its normal's impulse now.
void SubspaceSolver::ClampHeldFriction(const std::vector<int>& members, const std::vector<char>& held,
                                       std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies) {
  for (size_t i = 0; i < members.size(); ++i) {
    ConstraintRow& r = rows[members[i]];
    if (!held[i] || r.normal_row < 0) continue;
    const double bound = r.mu * std::max(0.0, rows[r.normal_row].lambda);
    const double clamped = std::clamp(r.lambda, -bound, bound);
    if (clamped != r.lambda) SetImpulse(r, clamped, bodies);
  }
}

int SubspaceSolver::SolveComponent(const std::vector<int>& members, std::vector<ConstraintRow>& rows,
                                   std::vector<SolverBody>& bodies, int passes, bool start_free) {
  const int m = static_cast<int>(members.size());
  BuildCoupling(members, rows, bodies);
  // free: solved for; held: kept at a bound (starting from the sweeps' guess)
  member_of_.assign(rows.size(), -1);
  for (int i = 0; i < m; ++i) member_of_[members[i]] = i;
  std::vector<char> held(m);
  for (int i = 0; i < m; ++i) {
    const ConstraintRow& r = rows[members[i]];
    double lo = r.lo, hi = r.hi;
    if (r.normal_row >= 0) hi = r.mu * rows[r.normal_row].lambda, lo = -hi;
    held[i] = diag_(i) <= 0.0 || (!start_free && (r.lambda <= lo || r.lambda >= hi));
  }
  std::vector<int> free_rows;
  int pass = 0;
  while (pass < passes) {
    ++pass;
    ClampHeldFriction(members, held, rows, bodies);
    free_rows.clear();
    position_.assign(m, -1);
    for (int i = 0; i < m; ++i) {
      if (held[i]) continue;
      position_[i] = static_cast<int>(free_rows.size());
      free_rows.push_back(i);
    }
    const int f = static_cast<int>(free_rows.size());
    if (f > 0) {
      // Jacobi-scaled A_SS y = D (rhs - J v), dlambda = D y, D = diag(A_SS)^-1/2
      Eigen::VectorXd b(f), scale(f);
      for (int i = 0; i < f; ++i) {
        const ConstraintRow& r = rows[members[free_rows[i]]];
        scale(i) = 1.0 / std::sqrt(diag_(free_rows[i]));
        b(i) = scale(i) * (r.rhs - r.Velocity(bodies) - r.cfm * r.lambda);
      }
      triplets_.clear();
      for (int col = 0; col < m; ++col) {
        if (position_[col] < 0) continue;
        for (Eigen::SparseMatrix<double>::InnerIterator it(A_, col); it; ++it) {
          const int row = static_cast<int>(it.row());
          if (position_[row] < 0) continue;
          const int pr = position_[row], pc = position_[col];
          triplets_.emplace_back(pr, pc, scale(pr) * it.value() * scale(pc));
        }
      }
      FillColumns(f, triplets_, &cursor_, &free_block_);  // column by column, rows ascending
      const Eigen::VectorXd dl = scale.cwiseProduct(MinNormSolve(free_block_, b, nullptr, &min_norm_cache_));
      const bool newly_held = start_free ? StepWithinBounds(members, free_rows, dl, held, rows, bodies)
                                         : ClampPastBounds(members, free_rows, dl, held, rows, bodies);
      if (newly_held) continue;
    }
    // held rows the solution leaves approaching (at lo) or pulling (at hi)
    // are freed; held friction too with release_friction (a friction row's
    // bounds are +-mu times its normal's impulse now)
    bool joined = false;
    for (int i = 0; i < m; ++i) {
      const ConstraintRow& r = rows[members[i]];
      if (!held[i] || diag_(i) <= 0.0 || (r.normal_row >= 0 && !release_friction_)) continue;
      double lo = r.lo, hi = r.hi;
      if (r.normal_row >= 0) hi = r.mu * std::max(0.0, rows[r.normal_row].lambda), lo = -hi;
      const double gap = r.rhs - r.Velocity(bodies) - r.cfm * r.lambda;  // > 0: wants more impulse
      const bool inside = r.normal_row >= 0 && r.lambda > lo && r.lambda < hi;
      if (inside || (r.lambda <= lo && gap > kJoinTolerance) || (r.lambda >= hi && gap < -kJoinTolerance)) {
        held[i] = false;
        joined = true;
      }
    }
    if (!joined) break;
  }
  ClampHeldFriction(members, held, rows, bodies);
  return pass;
}

}  // namespace contactsim
