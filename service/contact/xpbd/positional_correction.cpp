#include "service/contact/xpbd/positional_correction.h"

#include <cmath>
#include <utility>

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

namespace {

// The minimum-norm solution of S x = r for a symmetric positive
// semi-definite S (least squares for an r outside S's range), by Cholesky
// with complete (diagonal) pivoting (Higham 2002, "Accuracy and Stability of
// Numerical Algorithms", sec. 10.3): it stops at rank k, when the largest
// remaining diagonal is below 1e-10 of the first pivot, with S = B B^T and
// B (n x k) of full column rank, so that
//   S^+ = B (B^T B)^-1 (B^T B)^-1 B^T.
// A few times cheaper than a complete orthogonal decomposition of the same
// matrix, which this replaces (the same solution to rounding). Eigen's LDLT
// is no substitute: on these semi-definite blocks it does not keep its
// pivots in decreasing order and reports a numerical issue.
PairVector MinimumNormSolve(const PairMatrix& S, const PairVector& r) {
  const int n = static_cast<int>(S.rows());
  PairMatrix A = S;                      // the remaining Schur complement, permuted
  PairMatrix L = PairMatrix::Zero(n, n); // rows in the permuted order
  int perm[kMaxPairRows];
  for (int i = 0; i < n; ++i) perm[i] = i;
  int rank = 0;
  double first = 0.0;
  for (int k = 0; k < n; ++k) {
    int p = k;
    for (int i = k + 1; i < n; ++i) {
      if (A(i, i) > A(p, p)) p = i;
    }
    if (k == 0) first = A(p, p);
    if (!(A(p, p) > 1e-10 * first)) break;
    if (p != k) {
      A.row(k).swap(A.row(p));
      A.col(k).swap(A.col(p));
      L.row(k).swap(L.row(p));
      std::swap(perm[k], perm[p]);
    }
    const double d = std::sqrt(A(k, k));
    L(k, k) = d;
    for (int i = k + 1; i < n; ++i) L(i, k) = A(i, k) / d;
    for (int i = k + 1; i < n; ++i) {
      for (int j = k + 1; j < n; ++j) A(i, j) -= L(i, k) * L(j, k);
    }
    ++rank;
  }
  if (rank == 0) return PairVector::Zero(n);
  PairMatrix B(n, rank);
  for (int i = 0; i < n; ++i) B.row(perm[i]) = L.row(i).head(rank);
  const Eigen::LLT<PairMatrix> gram(B.transpose() * B);
  return B * gram.solve(gram.solve(B.transpose() * r));
}

}  // namespace

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
    const PairVector xs = MinimumNormSolve(Ks, rs);
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
