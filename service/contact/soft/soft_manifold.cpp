#include "service/contact/soft/soft_manifold.h"

#include <Eigen/Cholesky>
#include <algorithm>

namespace contactsim {
namespace {

constexpr int kMaxBlock = 4;

// The unit vector c with K c = 0 for four points of a face, or false when
// the points leave more than one such direction (three on a line). K c = 0
// when J^T c = 0: sum c_i = 0 (the rows' linear parts) and
// sum c_i (r_i x n) = (sum c_i r_i) x n = 0, the affine dependency of the
// points in the face's plane (r_Bi = r_Ai + x_A - x_B, the same for B). With
// (u, v) the points' coordinates along the tangents, c is the null vector
// of the 3 x 4 matrix [1; u; v], by cofactors.
bool FaceNullVector(const std::vector<SoftPoint>& points, const SoftManifold& m, Eigen::Vector4d* c) {
  const SoftPoint& p0 = points[m.first];
  double u[4], v[4];
  for (int i = 0; i < 4; ++i) {
    const Vec3 r = points[m.first + i].ra - p0.ra;
    u[i] = r.dot(p0.t1);
    v[i] = r.dot(p0.t2);
  }
  // c_j = (-1)^j det of [1; u; v] without column j
  auto minor = [&](int i, int j, int k) { return (u[j] - u[i]) * (v[k] - v[i]) - (u[k] - u[i]) * (v[j] - v[i]); };
  *c = Eigen::Vector4d(minor(1, 2, 3), -minor(0, 2, 3), minor(0, 1, 3), -minor(0, 1, 2));
  double extent = 0.0;
  for (int i = 1; i < 4; ++i) extent = std::max(extent, u[i] * u[i] + v[i] * v[i]);
  // every minor is zero (up to round-off) when the points lie on a line
  const double norm = c->norm();
  if (!(norm > 1e-9 * extent)) return false;
  *c /= norm;
  return true;
}

// K's pseudo-inverse for a face's four points: they act on three velocities
// (v_n and two tilts), so K is singular along c (FaceNullVector), and
// K^+ = (K + c c^T)^-1 - c c^T. dv = K^+ (v_n + bias) is the least-norm
// increment: it adds nothing along c (the corners' pattern + - + - on a
// square), so a symmetric face gets symmetric impulses however its points
// are ordered.
bool PseudoInvertFace(const std::vector<SoftPoint>& points, const SoftManifold& m, const Eigen::Matrix4d& k,
                      Eigen::Matrix4d* inv_k) {
  Eigen::Vector4d c;
  if (m.count != 4 || !FaceNullVector(points, m, &c)) return false;
  const Eigen::LLT<Eigen::Matrix4d> llt(k + c * c.transpose());
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Vector4d d = llt.matrixLLT().diagonal();
  if (d.minCoeff() <= 1e-5 * d.maxCoeff()) return false;
  *inv_k = llt.solve(Eigen::Matrix4d::Identity()) - c * c.transpose();
  return true;
}

// K_ij = n . (1/m_A + 1/m_B) n + (r_Ai x n) . I_A^-1 (r_Aj x n) + (r_Bi x n) . I_B^-1 (r_Bj x n)
bool InvertBlock(const std::vector<SoftPoint>& points, SoftManifold* m) {
  Eigen::Matrix4d k = Eigen::Matrix4d::Identity();
  for (int i = 0; i < m->count; ++i) {
    const SoftPoint& pi = points[m->first + i];
    if (pi.n.dot(points[m->first].n) < 1.0 - 1e-9) return false;
    for (int j = 0; j < m->count; ++j) {
      const SoftPoint& pj = points[m->first + j];
      k(i, j) = pi.mass_n > 0.0 ? pi.ra_n.dot(pj.ia_n) + pi.rb_n.dot(pj.ib_n) : 0.0;
    }
    // 1/m_A + 1/m_B from the point's own K: 1 / mass_n minus its angular part
    if (pi.mass_n > 0.0) k(i, i) = 1.0 / pi.mass_n;
  }
  // the linear part is the same for every pair of points
  const SoftPoint& p0 = points[m->first];
  const double k_lin = p0.mass_n > 0.0 ? 1.0 / p0.mass_n - p0.ra_n.dot(p0.ia_n) - p0.rb_n.dot(p0.ib_n) : 0.0;
  for (int i = 0; i < m->count; ++i) {
    for (int j = 0; j < m->count; ++j) {
      if (i != j) k(i, j) += k_lin;
    }
  }
  // K is symmetric positive semi-definite: a well-conditioned one is
  // inverted, a singular one (a face's four points) pseudo-inverted
  const Eigen::LLT<Eigen::Matrix4d> llt(k);
  if (llt.info() == Eigen::Success) {
    const Eigen::Vector4d d = llt.matrixLLT().diagonal();
    if (d.minCoeff() > 1e-5 * d.maxCoeff()) {
      m->inv_k = llt.solve(Eigen::Matrix4d::Identity());
      return true;
    }
  }
  return PseudoInvertFace(points, *m, k, &m->inv_k);
}

void SolveBlockNormals(const SoftPass& pass, const SoftManifold& m, std::vector<SoftPoint>& points,
                       std::vector<SoftBody>& bodies) {
  SoftBody& A = bodies[points[m.first].a];
  SoftBody& B = bodies[points[m.first].b];
  // the separations of points sharing n: n . dR r = (dR^T n) . r, so each
  // body's turn is applied to n once per block
  const Vec3& n = points[m.first].n;
  const double shift = n.dot(B.dp - A.dp);
  const Vec3 na = A.dR.transpose() * n, nb = B.dR.transpose() * n;
  const Vec3 dv = B.v - A.v;
  Eigen::Vector4d target = Eigen::Vector4d::Zero();
  SoftRowTarget rows[kMaxBlock];
  for (int i = 0; i < m.count; ++i) {
    const SoftPoint& p = points[m.first + i];
    const double s = shift + nb.dot(p.rb) - na.dot(p.ra) + p.adjusted_separation;
    rows[i] = SoftNormalTarget(pass, p, s);
    target[i] = n.dot(dv) + p.rb_n.dot(B.w) - p.ra_n.dot(A.w) + rows[i].bias;
  }
  const Eigen::Vector4d step = m.inv_k * target;
  double totals[kMaxBlock];
  for (int i = 0; i < m.count; ++i) {
    const SoftPoint& p = points[m.first + i];
    totals[i] = p.lambda_n - rows[i].mass_scale * step[i] - rows[i].impulse_scale * p.lambda_n;
    if (totals[i] < 0.0) {
      for (int j = 0; j < m.count; ++j) SolveSoftNormal(pass, points[m.first + j], A, B);
      return;
    }
  }
  // one update of each body for the whole block (the points share n)
  double sum = 0.0;
  Vec3 wa = Vec3::Zero(), wb = Vec3::Zero();
  for (int i = 0; i < m.count; ++i) {
    SoftPoint& p = points[m.first + i];
    const double applied = totals[i] - p.lambda_n;
    p.lambda_n = totals[i];
    p.max_push = std::max(p.max_push, applied);
    sum += applied;
    wa += applied * p.ia_n;
    wb += applied * p.ib_n;
  }
  A.v -= (A.inv_mass * sum) * n;
  A.w -= wa;
  B.v += (B.inv_mass * sum) * n;
  B.w += wb;
}

}  // namespace

void BuildSoftManifolds(const std::vector<SoftPoint>& points, std::vector<SoftManifold>* manifolds) {
  manifolds->clear();
  for (int k = 0; k < static_cast<int>(points.size()); ++k) {
    SoftManifold* last = manifolds->empty() ? nullptr : &manifolds->back();
    const bool same_pair = last != nullptr && last->count < kMaxBlock && points[last->first].a == points[k].a &&
                           points[last->first].b == points[k].b;
    if (same_pair) {
      ++last->count;
    } else {
      manifolds->push_back(SoftManifold{k, 1, false, Eigen::Matrix4d::Zero()});
    }
  }
  for (SoftManifold& m : *manifolds) {
    // a block of fewer points fills K's unused diagonal with 1 (identity rows)
    m.block = m.count >= 2 && InvertBlock(points, &m);
  }
}

void SolveSoftManifolds(const SoftPass& pass, const std::vector<SoftManifold>& manifolds,
                        std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) {
  for (const SoftManifold& m : manifolds) {
    SoftBody& A = bodies[points[m.first].a];
    SoftBody& B = bodies[points[m.first].b];
    for (int i = 0; i < m.count; ++i) SolveSoftFriction(points[m.first + i], A, B);
    if (m.block) {
      SolveBlockNormals(pass, m, points, bodies);
    } else {
      for (int i = 0; i < m.count; ++i) SolveSoftNormal(pass, points[m.first + i], A, B);
    }
  }
}

}  // namespace contactsim
