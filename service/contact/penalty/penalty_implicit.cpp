#include "service/contact/penalty/penalty_implicit.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

// One body's part of a row Jacobian: d . (v + w x r) = (d, r x d) . (v, w).
struct JacobianEntry {
  int body = -1;  // local index in the island
  Vec6 j = Vec6::Zero();
};
// A row's Jacobian: one entry per dynamic body of the pair (fixed storage:
// rows are built many times per active-set pass).
struct RowJacobian {
  JacobianEntry entries[2];
  int count = 0;
  void push_back(const JacobianEntry& e) { entries[count++] = e; }
  const JacobianEntry* begin() const { return entries; }
  const JacobianEntry* end() const { return entries + count; }
};
using Mat6 = Eigen::Matrix<double, 6, 6>;

enum class Friction { kStick, kSlide };

struct RowState {
  bool on = false;
  Friction friction = Friction::kStick;
  Vec3 s = Vec3::Zero();  // unit direction of a sliding point's friction force on B
};

class Island {
 public:
  // local: world index -> index in this island, shared by the islands
  Island(World& world, std::vector<PenaltyRow>& rows, double h, double theta, std::vector<int>& local)
      : world_(world), rows_(rows), h_(h), theta_(theta), local_(local) {}

  void AddBody(int index) {
    local_[index] = static_cast<int>(bodies_.size());
    bodies_.push_back(index);
  }
  void AddRow(int k) { members_.push_back(k); }

  ImplicitStats Solve(int max_iterations);

 private:
  RowJacobian Jacobian(const PenaltyRow& row, const Vec3& d) const {
    RowJacobian jac;
    const RigidBody& A = world_.bodies()[row.a];
    const RigidBody& B = world_.bodies()[row.b];
    if (B.IsDynamic()) jac.push_back({local_[row.b], (Vec6() << d, row.rb.cross(d)).finished()});
    if (A.IsDynamic()) jac.push_back({local_[row.a], (Vec6() << -d, -row.ra.cross(d)).finished()});
    return jac;
  }
  double Apply(const RowJacobian& jac, const Eigen::VectorXd& du) const {
    double sum = 0.0;
    for (const JacobianEntry& e : jac) sum += e.j.dot(du.segment<6>(6 * e.body));
    return sum;
  }
  // coef u v^T into the 6 x 6 blocks of the body pairs. Every block a row
  // touches is kept (rows switched off add coef 0), so that the sparsity
  // pattern stays the same across active-set passes and is analysed once
  // per step; summing into blocks first keeps the triplets at 36 per block
  // instead of 36 per row and body pair.
  Mat6& Block(int u, int v) {
    const auto [it, added] = block_index_.try_emplace({u, v}, static_cast<int>(blocks_.size()));
    if (added) blocks_.emplace_back(u, v, Mat6::Zero());
    return std::get<2>(blocks_[it->second]);
  }
  void AddOuter(const RowJacobian& u, const RowJacobian& v, double coef) {
    for (const JacobianEntry& eu : u) {
      for (const JacobianEntry& ev : v) Block(eu.body, ev.body).noalias() += (coef * eu.j) * ev.j.transpose();
    }
  }
  void AddRhs(const RowJacobian& u, double value) {
    for (const JacobianEntry& e : u) rhs_.segment<6>(6 * e.body) += value * e.j;
  }
  void Assemble(const std::vector<RowState>& state);
  // lambda(theta) and the friction force for the current du
  double NormalForce(const PenaltyRow& row, double g_du) const {
    const NormalLaw& l = row.law;
    return l.lambda0 - theta_ * l.k * h_ * row.vn0 - theta_ * (theta_ * l.k * h_ + l.c) * g_du;
  }

  World& world_;
  std::vector<PenaltyRow>& rows_;
  double h_, theta_;
  std::vector<int> bodies_;   // world indices, ascending
  std::vector<int>& local_;   // world index -> local index
  std::vector<int> members_;  // row indices
  std::vector<std::tuple<int, int, Mat6>> blocks_;   // (row body, column body, block), first-use order
  std::map<std::pair<int, int>, int> block_index_;   // into blocks_
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> A_;
  Eigen::VectorXd rhs_;
};

void Island::Assemble(const std::vector<RowState>& state) {
  const int n = static_cast<int>(bodies_.size());
  for (auto& block : blocks_) std::get<2>(block).setZero();
  rhs_.setZero(6 * n);
  for (int j = 0; j < n; ++j) {
    const RigidBody& b = world_.bodies()[bodies_[j]];
    Mat6& M = Block(j, j);
    M.topLeftCorner<3, 3>().diagonal().array() += b.mass;
    M.bottomRightCorner<3, 3>() += b.InertiaWorld();
    rhs_.segment<3>(6 * j) = h_ * b.force;
    rhs_.segment<3>(6 * j + 3) = h_ * b.torque;
  }
  for (size_t m = 0; m < members_.size(); ++m) {
    const RowState& st = state[m];
    const PenaltyRow& row = rows_[members_[m]];
    const NormalLaw& l = row.law;
    const RowJacobian g = Jacobian(row, row.n);
    if (!st.on) {
      AddOuter(g, g, 0.0);  // keeps the pattern
      continue;
    }
    const double coef_n = h_ * theta_ * (theta_ * l.k * h_ + l.c);
    const double base = l.lambda0 - theta_ * l.k * h_ * row.vn0;
    AddOuter(g, g, coef_n);
    AddRhs(g, h_ * base);
    if (row.mu <= 0.0) continue;
    if (st.friction == Friction::kStick) {
      const Vec3 f0 = row.TrialFriction() - theta_ * row.kt * h_ * row.vt0;
      const double coef_t = h_ * theta_ * (theta_ * row.kt * h_ + row.ct);
      for (const Vec3& t : {row.t1, row.t2}) {
        const RowJacobian jt = Jacobian(row, t);
        AddOuter(jt, jt, coef_t);
        AddRhs(jt, h_ * f0.dot(t));
      }
    } else {
      const RowJacobian js = Jacobian(row, st.s);
      AddOuter(js, g, row.mu * coef_n);
      AddRhs(js, h_ * row.mu * base);
    }
  }
  triplets_.clear();
  for (const auto& [u, v, block] : blocks_) {
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c < 6; ++c) triplets_.emplace_back(6 * u + r, 6 * v + c, block(r, c));
    }
  }
  A_.resize(6 * n, 6 * n);
  A_.setFromTriplets(triplets_.begin(), triplets_.end());
}

ImplicitStats Island::Solve(int max_iterations) {
  ImplicitStats stats;
  std::vector<RowState> state(members_.size());
  // start from the forces predicted with the velocities held (du = 0)
  for (size_t m = 0; m < members_.size(); ++m) {
    const PenaltyRow& row = rows_[members_[m]];
    const double lambda = NormalForce(row, 0.0);
    state[m].on = lambda > 0.0;
    const Vec3 f = row.TrialFriction() - theta_ * row.kt * h_ * row.vt0;
    if (f.norm() > row.mu * lambda && f.norm() > 0.0) {
      state[m].friction = Friction::kSlide;
      state[m].s = f.normalized();
    }
  }
  Eigen::VectorXd du;
  // Without sliding points the system is the mass matrix plus sums of
  // g g^T terms, symmetric positive definite: a sparse Cholesky (LDL^T)
  // solves it several times faster than the LU that a sliding point's
  // unsymmetric s g^T term needs. Each is analysed once per step.
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  bool lu_ready = false, ldlt_ready = false;
  for (int pass = 0; pass < max_iterations; ++pass) {
    ++stats.iterations;
    Assemble(state);
    const bool symmetric = std::none_of(state.begin(), state.end(), [](const RowState& st) {
      return st.on && st.friction == Friction::kSlide;
    });
    bool solved = false;
    if (symmetric) {
      if (!ldlt_ready) ldlt.analyzePattern(A_), ldlt_ready = true;
      ldlt.factorize(A_);
      solved = ldlt.info() == Eigen::Success;
      if (solved) du = ldlt.solve(rhs_);
    } else {
      if (!lu_ready) lu.analyzePattern(A_), lu_ready = true;
      lu.factorize(A_);
      solved = lu.info() == Eigen::Success;
      if (solved) du = lu.solve(rhs_);
    }
    if (!solved) du = Eigen::VectorXd::Constant(rhs_.size(), std::nan(""));
    bool changed = false;
    stats.residual = 0.0;
    for (size_t m = 0; m < members_.size(); ++m) {
      PenaltyRow& row = rows_[members_[m]];
      RowState& st = state[m];
      const double lambda = NormalForce(row, Apply(Jacobian(row, row.n), du));
      Vec3 tdu = Vec3::Zero();
      for (const Vec3& t : {row.t1, row.t2}) tdu += t * Apply(Jacobian(row, t), du);
      const Vec3 vt = row.vt0 + theta_ * tdu;  // slip velocity at the theta point
      row.lambda = st.on ? lambda : 0.0;
      row.ft.setZero();
      row.sliding = false;
      if (st.on != (lambda > 0.0)) {
        if (st.on) stats.residual = std::max(stats.residual, -lambda);
        st.on = lambda > 0.0;
        changed = true;
        continue;
      }
      if (!st.on || row.mu <= 0.0) continue;
      if (st.friction == Friction::kStick) {
        row.ft = row.TrialFriction() - theta_ * row.kt * h_ * row.vt0 -
                 theta_ * (theta_ * row.kt * h_ + row.ct) * tdu;
        const double excess = row.ft.norm() - row.mu * lambda;
        // relative slack: round-off must not flip a point sitting on the cone
        if (excess > 1e-9 * row.mu * lambda + 1e-12) {
          st.friction = Friction::kSlide;
          st.s = row.ft.normalized();
          stats.residual = std::max(stats.residual, excess);
          changed = true;
        }
      } else {
        row.ft = row.mu * lambda * st.s;
        row.sliding = true;
        if (vt.dot(st.s) > 0.0) {  // friction reversed the slip: it sticks
          st.friction = Friction::kStick;
          changed = true;
        }
      }
    }
    if (!changed) {
      stats.residual = 0.0;
      break;
    }
  }
  // new momenta: P += m dv, L += I dw (I at the step's start, as in M)
  for (size_t j = 0; j < bodies_.size(); ++j) {
    RigidBody& b = world_.bodies()[bodies_[j]];
    if (!du.segment<6>(6 * j).allFinite()) continue;  // a singular island keeps its momenta
    b.P += b.mass * du.segment<3>(6 * j);
    b.L += b.InertiaWorld() * du.segment<3>(6 * j + 3);
  }
  return stats;
}

}  // namespace

ImplicitStats ImplicitMomentumStep(World& world, std::vector<PenaltyRow>& rows, double h, double theta,
                                   int max_iterations) {
  auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  UnionFind islands(n);
  std::vector<bool> in_contact(n, false);
  for (const PenaltyRow& row : rows) {
    if (!row.engaged) continue;
    const bool da = bodies[row.a].IsDynamic(), db = bodies[row.b].IsDynamic();
    if (da) in_contact[row.a] = true;
    if (db) in_contact[row.b] = true;
    if (da && db) islands.Join(row.a, row.b);
  }
  // bodies and rows of each island, named by its first body
  std::vector<std::vector<int>> island_bodies(n), island_rows(n);
  for (int i = 0; i < n; ++i) {
    if (in_contact[i]) island_bodies[islands.Root(i)].push_back(i);
  }
  for (size_t k = 0; k < rows.size(); ++k) {
    const PenaltyRow& row = rows[k];
    if (!row.engaged) continue;
    const int body = bodies[row.a].IsDynamic() ? row.a : row.b;
    island_rows[islands.Root(body)].push_back(static_cast<int>(k));
  }
  ImplicitStats total;
  std::vector<int> local(n, -1);
  for (int root = 0; root < n; ++root) {
    if (island_bodies[root].empty()) continue;
    Island island(world, rows, h, theta, local);
    for (int i : island_bodies[root]) island.AddBody(i);
    for (int k : island_rows[root]) island.AddRow(k);
    const ImplicitStats s = island.Solve(max_iterations);
    total.iterations += s.iterations;
    total.residual = std::max(total.residual, s.residual);
  }
  for (int i = 0; i < n; ++i) {
    if (!bodies[i].IsDynamic() || in_contact[i]) continue;
    bodies[i].P += bodies[i].force * h;
    bodies[i].L += bodies[i].torque * h;
  }
  return total;
}

}  // namespace contactsim
