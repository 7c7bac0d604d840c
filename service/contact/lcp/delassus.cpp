#include "service/contact/lcp/delassus.h"

namespace contactsim {

MatX DenseDelassus(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies) {
  const int m = static_cast<int>(rows.size());
  MatX G = MatX::Zero(m, m);
  // per body, the rows acting on it with their Jacobian blocks
  struct Side {
    int row;
    Vec3 lin, ang;
  };
  std::vector<std::vector<Side>> by_body(bodies.size());
  for (int k = 0; k < m; ++k) {
    const ConstraintRow& r = rows[k];
    if (r.a >= 0 && bodies[r.a].inv_mass > 0.0) by_body[r.a].push_back({k, r.lin_a, r.ang_a});
    if (r.b >= 0 && bodies[r.b].inv_mass > 0.0) by_body[r.b].push_back({k, r.lin_b, r.ang_b});
  }
  for (size_t i = 0; i < bodies.size(); ++i) {
    const SolverBody& body = bodies[i];
    for (const Side& s : by_body[i]) {
      const Vec3 m_lin = body.inv_mass * s.lin;
      const Vec3 m_ang = body.inv_inertia * s.ang;
      for (const Side& t : by_body[i]) G(t.row, s.row) += t.lin.dot(m_lin) + t.ang.dot(m_ang);
    }
  }
  return G;
}

VecX RowVelocities(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies) {
  VecX u(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) u[k] = rows[k].Velocity(bodies);
  return u;
}

}  // namespace contactsim
