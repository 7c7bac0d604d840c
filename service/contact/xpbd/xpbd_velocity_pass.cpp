#include "service/contact/xpbd/xpbd_velocity_pass.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

// The normal impulse dl n on B and -dl n on A.
void PushNormal(double dl, const XpbdPoint& p, SoftBody& A, SoftBody& B) {
  A.v -= (A.inv_mass * dl) * p.n;
  A.w -= dl * p.ia_n;
  B.v += (B.inv_mass * dl) * p.n;
  B.w += dl * p.ib_n;
}

double NormalVelocity(const XpbdPoint& p, const SoftBody& A, const SoftBody& B) {
  return p.n.dot(B.v - A.v) + p.rb_n.dot(B.w) - p.ra_n.dot(A.w);
}

// The normal velocity a point that pushed leaves with: -e v~_n after an
// impact faster than the threshold, 0 after a slower one; a point already
// parting before the solve (v~_n > 0: an overlap left from an earlier
// sub-step) keeps v~_n, so pushing out adds no velocity.
double TargetNormalVelocity(const XpbdPoint& p, double threshold) {
  if (p.vn_before >= 0.0) return p.vn_before;
  const double e = -p.vn_before > threshold ? p.restitution : 0.0;
  return -e * p.vn_before;
}

// Restitution of a block's points that pushed, all at once through the
// inverse of their K (K^+ for a face's four), so the corners of a face
// share it whatever their order; point by point where no block applies.
void SolveBlockRestitution(double threshold, const NormalBlock& m, XpbdSubsetCache& cache,
                           const std::vector<SoftBody>& all, SoftBody& A, SoftBody& B, std::vector<XpbdPoint>& points) {
  int idx[kMaxNormalBlock];
  int pushed = 0;
  for (int i = 0; i < m.count; ++i) {
    if (points[m.first + i].lambda_n > 0.0) idx[pushed++] = i;
  }
  if (pushed == 0) return;
  if (const Eigen::Matrix4d* inv = XpbdSubsetInverse(points, all, m, idx, pushed, cache)) {
    Eigen::Vector4d change = Eigen::Vector4d::Zero();
    for (int k = 0; k < pushed; ++k) {
      const XpbdPoint& p = points[m.first + idx[k]];
      change[k] = TargetNormalVelocity(p, threshold) - NormalVelocity(p, A, B);
    }
    const Eigen::Vector4d dl = *inv * change;
    for (int k = 0; k < pushed; ++k) {
      XpbdPoint& p = points[m.first + idx[k]];
      PushNormal(dl[k], p, A, B);
      p.impulse += dl[k] * p.n;
    }
    return;
  }
  for (int k = 0; k < pushed; ++k) {
    XpbdPoint& p = points[m.first + idx[k]];
    if (p.w_n <= 0.0) continue;
    const double dl = (TargetNormalVelocity(p, threshold) - NormalVelocity(p, A, B)) / p.w_n;
    PushNormal(dl, p, A, B);
    p.impulse += dl * p.n;
  }
}

}  // namespace

void SolveXpbdContactVelocities(double h, double restitution_threshold, const std::vector<NormalBlock>& blocks,
                                const std::vector<XpbdPatch>& patches, std::vector<XpbdSubsetCache>& caches,
                                std::vector<SoftBody>& bodies, std::vector<XpbdPoint>* points) {
  for (size_t k = 0; k < blocks.size(); ++k) {
    const NormalBlock& m = blocks[k];
    SoftBody& A = bodies[(*points)[m.first].a];
    SoftBody& B = bodies[(*points)[m.first].b];
    SolveBlockRestitution(restitution_threshold, m, caches[k], bodies, A, B, *points);
    BrakeXpbdPatch(h, patches[k], A, B, *points);
  }
}

}  // namespace contactsim
