#include "service/contact/soft/soft_manifold.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>

namespace contactsim {
namespace {

constexpr int kMaxBlock = 4;

// K's pseudo-inverse when it lacks one rank at most (the four points of a
// face act on three velocities: v_n and two tilts): dv = K^+ (v_n + bias) is
// the least-norm increment, which adds nothing along K's null space (the
// corners' pattern + - + -), so a symmetric face gets symmetric impulses
// however its points are ordered. Fewer ranks (points on a line, a point
// repeated): no block.
bool PseudoInvert(const Eigen::Matrix4d& k, int count, Eigen::Matrix4d* inv_k) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(k);
  const Eigen::Vector4d ev = eig.eigenvalues();
  const double cut = 1e-8 * ev.cwiseAbs().maxCoeff();
  Eigen::Vector4d inv = Eigen::Vector4d::Zero();
  int rank = 0;
  for (int i = 0; i < 4; ++i) {
    if (ev[i] > cut) {
      inv[i] = 1.0 / ev[i];
      ++rank;
    }
  }
  // the unused rows of a smaller block are identity rows and count too
  if (rank < 4 - (count == 4 ? 1 : 0)) return false;
  *inv_k = eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
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
  return PseudoInvert(k, m->count, &m->inv_k);
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
