#include "service/contact/xpbd/positional_correction.h"

namespace contactsim {

double GeneralizedInverseMass(const RigidBody& body, const Vec3& r, const Vec3& n) {
  if (!body.IsDynamic()) return 0.0;
  const Vec3 rn = r.cross(n);
  return body.inv_mass + rn.dot(body.InvInertiaWorld() * rn);
}

void ApplyPositionalImpulse(RigidBody& body, const Vec3& p, const Vec3& r) {
  if (!body.IsDynamic()) return;
  body.x += p * body.inv_mass;
  ApplyAngularPositionalImpulse(body, r.cross(p));
}

void ApplyAngularPositionalImpulse(RigidBody& body, const Vec3& h) {
  if (!body.IsDynamic()) return;
  const Vec3 phi = body.InvInertiaWorld() * h;
  // q += 1/2 [phi, 0] q, then renormalised (eq. 8)
  const Quat dq = Quat(0.0, phi.x(), phi.y(), phi.z()) * body.q;
  body.q.coeffs() += 0.5 * dq.coeffs();
  body.q.normalize();
}

double SolvePositionalConstraint(RigidBody& a, const Vec3& ra, RigidBody& b, const Vec3& rb, const Vec3& n,
                                 double c, double alpha_tilde, double* lambda) {
  const double w = GeneralizedInverseMass(a, ra, n) + GeneralizedInverseMass(b, rb, n) + alpha_tilde;
  if (w <= 0.0) return 0.0;
  const double dlambda = (c - alpha_tilde * *lambda) / w;
  *lambda += dlambda;
  const Vec3 p = dlambda * n;
  ApplyPositionalImpulse(b, p, rb);
  ApplyPositionalImpulse(a, -p, ra);
  return dlambda;
}

double SolveAngularConstraint(RigidBody& a, RigidBody& b, const Vec3& n, double c, double alpha_tilde,
                              double* lambda) {
  const double wa = a.IsDynamic() ? n.dot(a.InvInertiaWorld() * n) : 0.0;
  const double wb = b.IsDynamic() ? n.dot(b.InvInertiaWorld() * n) : 0.0;
  const double w = wa + wb + alpha_tilde;
  if (w <= 0.0) return 0.0;
  const double dlambda = (c - alpha_tilde * *lambda) / w;
  *lambda += dlambda;
  ApplyAngularPositionalImpulse(b, dlambda * n);
  ApplyAngularPositionalImpulse(a, -dlambda * n);
  return dlambda;
}

}  // namespace contactsim

namespace contactsim {

PairMatrix PairCoupling(const RigidBody& a, const RigidBody& b, const std::vector<PairRow>& rows) {
  const int m = static_cast<int>(rows.size());
  PairMatrix K = PairMatrix::Zero(m, m);
  const RigidBody* body[2] = {&a, &b};
  for (int side = 0; side < 2; ++side) {
    const RigidBody& s = *body[side];
    if (!s.IsDynamic()) continue;
    const Mat3 inv_I = s.InvInertiaWorld();
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxPairRows> arm(3, m), d(3, m);
    for (int k = 0; k < m; ++k) {
      arm.col(k) = (side == 0 ? rows[k].ra : rows[k].rb).cross(rows[k].d);
      d.col(k) = rows[k].d;
    }
    K.noalias() += s.inv_mass * d.transpose() * d;
    K.noalias() += arm.transpose() * (inv_I * arm);
  }
  return K;
}

PairVector SolvePairBlock(const RigidBody& a, const RigidBody& b, const std::vector<PairRow>& rows,
                          const std::vector<double>& rhs, double alpha_tilde, bool nonnegative) {
  const PairMatrix K = PairCoupling(a, b, rows);
  const int m = static_cast<int>(rhs.size());
  PairVector x = PairVector::Zero(m);
  int active[kMaxPairRows];
  int n = m;
  for (int k = 0; k < m; ++k) active[k] = k;
  while (n > 0) {
    PairMatrix Ks(n, n);
    PairVector rs(n);
    for (int i = 0; i < n; ++i) {
      rs(i) = rhs[active[i]];
      for (int j = 0; j < n; ++j) Ks(i, j) = K(active[i], active[j]);
      Ks(i, i) += alpha_tilde;
    }
    // minimum norm (least squares) by a complete orthogonal decomposition;
    // a pivoted Cholesky S = B B^T with S^+ = B (B^T B)^-2 B^T was 1.6x
    // faster on the pyramid but let box_rain's boxes explode at step 125.
    // The rank is Eigen's default (pivots below n eps of the largest are
    // zero): a face's rank-3 matrix is taken as rank 3 and every other
    // block solved exactly. A threshold of 1e-10 solved nearly singular
    // blocks by least squares, and a five-box stack moved 12 mm in 10 s
    // instead of 7 um; set after compute() it also made solve() apply a Z
    // that compute() never built (uninitialised memory, so each build
    // computed its own physics)
    const Eigen::CompleteOrthogonalDecomposition<PairMatrix> cod(Ks);
    const PairVector xs = cod.solve(rs);
    int worst = -1;
    for (int i = 0; i < n; ++i) {
      if (nonnegative && xs(i) < 0.0 && (worst < 0 || xs(i) < xs(worst))) worst = i;
    }
    if (worst < 0) {
      x.setZero();
      for (int i = 0; i < n; ++i) x(active[i]) = xs(i);
      return x;
    }
    for (int i = worst; i + 1 < n; ++i) active[i] = active[i + 1];
    --n;
  }
  return x;
}

void ApplyPairPositional(RigidBody& a, RigidBody& b, const std::vector<PairRow>& rows, const PairVector& x) {
  Vec3 p = Vec3::Zero(), ha = Vec3::Zero(), hb = Vec3::Zero();
  for (size_t k = 0; k < rows.size(); ++k) {
    const Vec3 pk = x(k) * rows[k].d;
    p += pk;
    hb += rows[k].rb.cross(pk);
    ha -= rows[k].ra.cross(pk);
  }
  if (a.IsDynamic()) {
    a.x -= p * a.inv_mass;
    ApplyAngularPositionalImpulse(a, ha);
  }
  if (b.IsDynamic()) {
    b.x += p * b.inv_mass;
    ApplyAngularPositionalImpulse(b, hb);
  }
}

}  // namespace contactsim
