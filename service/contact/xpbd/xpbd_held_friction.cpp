#include "service/contact/xpbd/xpbd_held_friction.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "service/contact/xpbd/xpbd_patch_friction.h"

namespace contactsim {
namespace {

// S^-1 of a symmetric positive definite S, false when S is singular to
// within round-off of its largest diagonal (a row S cannot move).
template <int N>
bool InvertSpd(const Eigen::Matrix<double, N, N>& s, Eigen::Matrix<double, N, N>* inv) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(s);
  if (llt.info() != Eigen::Success) return false;
  const auto d = llt.matrixLLT().diagonal();
  if (!(d.minCoeff() > 1e-6 * d.maxCoeff())) return false;
  *inv = llt.solve(Eigen::Matrix<double, N, N>::Identity());
  return true;
}

// The friction rows' Jacobians on B (A's are their negatives, so products
// of A's parts carry the same sign as B's): t1, t2 at the centre, the twist.
struct RowJacobians {
  Vec3 lin[3], ang_a[3], ang_b[3];
  explicit RowJacobians(const XpbdFrictionRows& rows)
      : lin{rows.t1, rows.t2, Vec3::Zero()},
        ang_a{rows.ra.cross(rows.t1), rows.ra.cross(rows.t2), rows.n},
        ang_b{rows.rb.cross(rows.t1), rows.rb.cross(rows.t2), rows.n} {}
};

// Point p's row of K against the friction rows:
// K_pj = k_lin n_p . t_j + ia_n_p . ang_a_j + ib_n_p . ang_b_j.
Vec3 FrictionCoupling(const XpbdPoint& p, double k_lin, const RowJacobians& j) {
  Vec3 k;
  for (int c = 0; c < 3; ++c) k[c] = k_lin * p.n.dot(j.lin[c]) + p.ia_n.dot(j.ang_a[c]) + p.ib_n.dot(j.ang_b[c]);
  return k;
}

// K between two normal rows (xpbd_contact.h, XpbdPoint::k_lin).
double NormalCoupling(const XpbdPoint& p, const XpbdPoint& q, double k_lin) {
  return k_lin * p.n.dot(q.n) + p.ra_n.dot(q.ia_n) + p.rb_n.dot(q.ib_n);
}

}  // namespace

bool BuildXpbdHeldRows(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies,
                       const NormalBlock& block, XpbdSubsetCache& cache, const XpbdFrictionRows& rows,
                       const int* idx, int count, XpbdHeldRows* held) {
  held->mask = 0;
  for (int k = 0; k < count; ++k) held->mask |= 1 << idx[k];
  held->ok = held->ok_tangent = false;
  const Eigen::Matrix4d* inv = XpbdSubsetInverse(points, bodies, block, idx, count, cache);
  if (inv == nullptr) return false;
  held->inv_nn = *inv;
  const XpbdPoint& p0 = points[block.first];
  const double k_lin = bodies[p0.a].inv_mass + bodies[p0.b].inv_mass;
  const RowJacobians jac(rows);
  Eigen::Matrix<double, kMaxNormalBlock, 3> k_nf = Eigen::Matrix<double, kMaxNormalBlock, 3>::Zero();
  for (int k = 0; k < count; ++k) k_nf.row(k) = FrictionCoupling(points[block.first + idx[k]], k_lin, jac);
  held->g.noalias() = *inv * k_nf;
  Eigen::Matrix3d s = *rows.k_ff - k_nf.transpose() * held->g;
  s = 0.5 * (s + s.transpose());
  held->ok_tangent = InvertSpd<2>(Eigen::Matrix2d(s.topLeftCorner<2, 2>()), &held->s2_inv);
  if (rows.twist) {
    held->ok = InvertSpd<3>(s, &held->s_inv);
  } else {
    held->ok = held->ok_tangent;
    held->s_inv.setZero();
    held->s_inv.topLeftCorner<2, 2>() = held->s2_inv;
  }
  return held->ok;
}

namespace {

// The held solve of one set: the friction step dl_f for `slip` (the twist
// row left out unless `twist`) and the held points' pushes dl_n that bring
// them to depth d (0 for points that push, the gap of a point joining).
void HeldStep(const XpbdHeldRows& held, const Vec3& slip, const Eigen::Vector4d& d, bool twist, int count,
              Vec3* dl_f, Eigen::Vector4d* dl_n) {
  const Vec3 rhs = slip - held.g.transpose() * d;
  if (twist) {
    *dl_f = held.s_inv * rhs;
  } else {
    dl_f->head<2>() = held.s2_inv * rhs.head<2>();
    (*dl_f)[2] = 0.0;
  }
  *dl_n = held.inv_nn * d - held.g * *dl_f;
  for (int k = count; k < kMaxNormalBlock; ++k) (*dl_n)[k] = 0.0;
}

// The bodies moved by the friction step dl_f at the patch's centre and the
// held points' pushes dl_n, which join their lambda_n.
void ApplyHeldStep(World& world, const std::vector<SoftBody>& bodies, const XpbdPatch& patch, const int* idx,
                   int count, const Vec3& dl_f, const Eigen::Vector4d& dl_n, std::vector<XpbdPoint>& points) {
  const XpbdPoint& p0 = points[patch.first];
  const Vec3& n = p0.n;
  const Vec3 P = dl_f[0] * patch.t1 + dl_f[1] * patch.t2;
  double sum = 0.0;
  Vec3 wa = Vec3::Zero(), wb = Vec3::Zero();
  for (int k = 0; k < count; ++k) {
    XpbdPoint& p = points[patch.first + idx[k]];
    p.lambda_n += dl_n[k];
    sum += dl_n[k];
    wa += dl_n[k] * p.ia_n;
    wb += dl_n[k] * p.ib_n;
  }
  const SoftBody& sa = bodies[p0.a];
  const SoftBody& sb = bodies[p0.b];
  const Vec3 force = P + sum * n;
  DisplaceXpbdBody(world.bodies()[p0.a], sa, -sa.inv_mass * force,
                   -(sa.inv_inertia * (patch.ra.cross(P) + dl_f[2] * n) + wa));
  DisplaceXpbdBody(world.bodies()[p0.b], sb, sb.inv_mass * force,
                   sb.inv_inertia * (patch.rb.cross(P) + dl_f[2] * n) + wb);
}

// Changes to the held set so far, at most: each point joins or leaves a
// few times before the set settles (the normal block's loop takes at most
// four).
constexpr int kMaxHeldChanges = 8;

}  // namespace

bool SolveHeldXpbdPatchFriction(World& world, const std::vector<SoftBody>& bodies, const NormalBlock& block,
                                XpbdSubsetCache& cache, const Vec3& slip, const Vec3& offset, double pushed,
                                XpbdPatch& patch, std::vector<XpbdPoint>& points) {
  const XpbdPoint& p0 = points[patch.first];
  const XpbdFrictionRows rows{patch.t1, patch.t2, p0.n, patch.ra, patch.rb, &patch.k, patch.twist_radius > 0.0};
  const RowJacobians jac(rows);
  const double k_lin = bodies[p0.a].inv_mass + bodies[p0.b].inv_mass;
  // the held set: the points that push, at depth 0 after their block's
  // solve; a point the friction step would push into the other body joins
  // at its present gap
  int idx[kMaxNormalBlock];
  double gap[kMaxNormalBlock];  // m, the block's points' depths (<= 0) when they join
  bool held[kMaxNormalBlock] = {false, false, false, false};
  int count = 0;
  for (int i = 0; i < patch.count; ++i) {
    gap[i] = 0.0;
    if (points[patch.first + i].lambda_n > 0.0) {
      idx[count++] = i;
      held[i] = true;
    }
  }
  const double mu = patch.friction;
  bool twist = rows.twist;
  Vec3 dl_f = Vec3::Zero();
  Eigen::Vector4d dl_n = Eigen::Vector4d::Zero();
  double held_sum = pushed;
  for (int change = 0;; ++change) {
    if (count == 0 || change > kMaxHeldChanges) return false;
    int mask = 0;
    for (int k = 0; k < count; ++k) mask |= 1 << idx[k];
    if (patch.held.mask != mask) BuildXpbdHeldRows(points, bodies, block, cache, rows, idx, count, &patch.held);
    if (!patch.held.ok || (!twist && !patch.held.ok_tangent)) return false;
    Eigen::Vector4d d = Eigen::Vector4d::Zero();
    for (int k = 0; k < count; ++k) d[k] = gap[idx[k]];
    HeldStep(patch.held, slip, d, twist, count, &dl_f, &dl_n);
    held_sum = pushed + dl_n.sum();
    if (twist && std::abs(patch.lambda_twist + dl_f[2]) > mu * held_sum * patch.twist_radius) {
      twist = false;  // it spins: the tangent rows alone
      continue;
    }
    // a held point whose push would pull leaves the set
    int worst = -1;
    double worst_total = 0.0;
    for (int k = 0; k < count; ++k) {
      const double total = points[patch.first + idx[k]].lambda_n + dl_n[k];
      if (total < worst_total) {
        worst = k;
        worst_total = total;
      }
    }
    if (worst >= 0) {
      held[idx[worst]] = false;
      for (int k = worst; k + 1 < count; ++k) idx[k] = idx[k + 1];
      --count;
      continue;
    }
    // a free point the step would push into the other body joins it
    int join = -1;
    double join_depth = 0.0;
    for (int i = 0; i < patch.count; ++i) {
      if (held[i]) continue;
      const XpbdPoint& p = points[patch.first + i];
      const double depth = -XpbdSeparation(p, world);
      double closing = FrictionCoupling(p, k_lin, jac).dot(dl_f);
      for (int k = 0; k < count; ++k) closing += NormalCoupling(p, points[patch.first + idx[k]], k_lin) * dl_n[k];
      // depth after the step: the pushes and the friction move the point by -closing along n
      const double after = depth - closing;
      if (after > join_depth) {
        join = i;
        join_depth = after;
        gap[i] = std::min(depth, 0.0);
      }
    }
    if (join < 0 || count == kMaxNormalBlock) break;
    held[join] = true;
    idx[count++] = join;
    std::sort(idx, idx + count);
  }
  patch.sticking = false;
  const Vec3 lambda_t = patch.lambda_t + dl_f[0] * patch.t1 + dl_f[1] * patch.t2;
  // the cone over the step (xpbd_patch_friction.h)
  if (!((patch.step_lambda_t + lambda_t).norm() <= mu * (patch.step_pushed + held_sum))) {  // the patch slides
    patch.origin = offset;
    return true;
  }
  patch.sticking = true;
  if (rows.twist && !twist) patch.origin[2] = offset[2];  // it spins: hold the translation only
  patch.lambda_t = lambda_t;
  patch.lambda_twist += dl_f[2];
  patch.pushed = held_sum;
  ApplyHeldStep(world, bodies, patch, idx, count, dl_f, dl_n, points);
  return true;
}

}  // namespace contactsim
