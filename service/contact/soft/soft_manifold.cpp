#include "service/contact/soft/soft_manifold.h"

#include <algorithm>


namespace contactsim {
namespace {

// manifolds a thread inverts at a time
constexpr int kInvertGrain = 128;

bool InvertBlock(const std::vector<SoftPoint>& points, SoftManifold* m) {
  const SoftPoint& p0 = points[m->first];
  if (p0.mass_n <= 0.0) return false;
  NormalBlockPoint block[kMaxNormalBlock];
  for (int i = 0; i < m->count; ++i) {
    const SoftPoint& p = points[m->first + i];
    if (p.n.dot(p0.n) < 1.0 - 1e-9) return false;
    block[i] = {p.ra, p.ra_n, p.rb_n, p.ia_n, p.ib_n};
  }
  // 1/m_A + 1/m_B: a point's K minus its angular part
  const double k_lin = 1.0 / p0.mass_n - p0.ra_n.dot(p0.ia_n) - p0.rb_n.dot(p0.ib_n);
  return InvertNormalBlock(block, m->count, k_lin, p0.t1, p0.t2, &m->inv_k);
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
  SoftRowTarget rows[kMaxNormalBlock];
  for (int i = 0; i < m.count; ++i) {
    const SoftPoint& p = points[m.first + i];
    const double s = shift + nb.dot(p.rb) - na.dot(p.ra) + p.adjusted_separation;
    rows[i] = SoftNormalTarget(pass, p, s);
    target[i] = n.dot(dv) + p.rb_n.dot(B.w) - p.ra_n.dot(A.w) + rows[i].bias;
  }
  const Eigen::Vector4d step = m.inv_k * target;
  double totals[kMaxNormalBlock];
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
  if (A.inv_mass > 0.0) {
    A.v -= (A.inv_mass * sum) * n;
    A.w -= wa;
  }
  if (B.inv_mass > 0.0) {
    B.v += (B.inv_mass * sum) * n;
    B.w += wb;
  }
}

}  // namespace

void BuildSoftManifolds(const std::vector<SoftPoint>& points, ParallelRunner& runner,
                        std::vector<SoftManifold>* manifolds, bool invert) {
  GroupNormalBlocks(points, &SoftPoint::n, manifolds);
  if (invert) InvertSoftManifolds(points, runner, manifolds);
}

void InvertSoftManifolds(const std::vector<SoftPoint>& points, ParallelRunner& runner,
                         std::vector<SoftManifold>* manifolds) {
  runner.For(static_cast<int>(manifolds->size()), kInvertGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) InvertSoftManifold(points, &(*manifolds)[k]);
  });
}

void InvertSoftManifold(const std::vector<SoftPoint>& points, SoftManifold* m) {
  m->block = m->count >= 2 && InvertBlock(points, m);
}

void SolveSoftManifolds(const SoftPass& pass, const std::vector<SoftManifold>& manifolds, int begin, int end,
                        std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) {
  for (int k = begin; k < end; ++k) {
    const SoftManifold& m = manifolds[k];
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
