#include "service/contact/joints/joint_dense_solver.h"

#include <Eigen/Cholesky>

#include "service/contact/joints/joint_rows.h"

namespace contactsim {
namespace {

// M^-1 J_k^T restricted to one body: (inv_mass lin, I^-1 ang)
double Coupling(const Vec3& lin_k, const Vec3& ang_k, const Vec3& lin_l, const Vec3& ang_l, const SolverBody& s) {
  return s.inv_mass * lin_k.dot(lin_l) + ang_k.dot(s.inv_inertia * ang_l);
}

}  // namespace

Eigen::MatrixXd JointSystemMatrix(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies) {
  const int n = static_cast<int>(rows.size());
  // rows touching each body, so that only pairs sharing a body are visited
  std::vector<std::vector<std::pair<int, bool>>> touching(bodies.size());  // (row, side is A)
  for (int k = 0; k < n; ++k) {
    if (rows[k].a >= 0 && bodies[rows[k].a].inv_mass > 0.0) touching[rows[k].a].push_back({k, true});
    if (rows[k].b >= 0 && bodies[rows[k].b].inv_mass > 0.0) touching[rows[k].b].push_back({k, false});
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (size_t i = 0; i < bodies.size(); ++i) {
    for (const auto& [k, k_on_a] : touching[i]) {
      const Vec3& lin_k = k_on_a ? rows[k].lin_a : rows[k].lin_b;
      const Vec3& ang_k = k_on_a ? rows[k].ang_a : rows[k].ang_b;
      for (const auto& [l, l_on_a] : touching[i]) {
        const Vec3& lin_l = l_on_a ? rows[l].lin_a : rows[l].lin_b;
        const Vec3& ang_l = l_on_a ? rows[l].ang_a : rows[l].ang_b;
        A(k, l) += Coupling(lin_k, ang_k, lin_l, ang_l, bodies[i]);
      }
    }
  }
  for (int k = 0; k < n; ++k) A(k, k) = A(k, k) * (1.0 + kJointRegularisation) + rows[k].cfm;
  return A;
}

Eigen::VectorXd SolveJointsDense(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                                 const Eigen::VectorXd& b) {
  if (rows.empty()) return Eigen::VectorXd();
  return JointSystemMatrix(rows, bodies).ldlt().solve(b);
}

}  // namespace contactsim
