#include "service/contact/soft/soft_manifold.h"

#include <Eigen/LU>

namespace contactsim {
namespace {

constexpr int kMaxBlock = 4;

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
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(k);
  // rank-deficient (four points on a line, a point repeated): no block
  if (lu.rank() < kMaxBlock || lu.rcond() < 1e-10) return false;
  m->inv_k = lu.inverse();
  return true;
}

void SolveBlockNormals(const SoftPass& pass, const SoftManifold& m, std::vector<SoftPoint>& points,
                       std::vector<SoftBody>& bodies) {
  SoftBody& A = bodies[points[m.first].a];
  SoftBody& B = bodies[points[m.first].b];
  Eigen::Vector4d target = Eigen::Vector4d::Zero();
  SoftRowTarget rows[kMaxBlock];
  for (int i = 0; i < m.count; ++i) {
    const SoftPoint& p = points[m.first + i];
    rows[i] = SoftNormalTarget(pass, p, A, B);
    target[i] = p.VelocityAlong(p.n, p.ra_n, p.rb_n, A, B) + rows[i].bias;
  }
  const Eigen::Vector4d dv = m.inv_k * target;
  double totals[kMaxBlock];
  for (int i = 0; i < m.count; ++i) {
    const SoftPoint& p = points[m.first + i];
    totals[i] = p.lambda_n - rows[i].mass_scale * dv[i] - rows[i].impulse_scale * p.lambda_n;
    if (totals[i] < 0.0) {
      for (int j = 0; j < m.count; ++j) SolveSoftNormal(pass, points[m.first + j], A, B);
      return;
    }
  }
  for (int i = 0; i < m.count; ++i) ApplySoftNormal(totals[i], points[m.first + i], A, B);
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
