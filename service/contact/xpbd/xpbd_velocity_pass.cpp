#include "service/contact/xpbd/xpbd_velocity_pass.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "service/contact/push_impulse.h"

namespace contactsim {
namespace {

double NormalVelocity(const XpbdPoint& p, const SoftBody& A, const SoftBody& B) {
  return XpbdNormalVelocity(p, A.v, A.w, B.v, B.w);
}

// The normal velocity a point that pushed leaves with: -e v~_n after an
// impact faster than the threshold, 0 after a slower one; a point already
// parting before the solve (v~_n > 0: an overlap left from an earlier
// sub-step) keeps v~_n, so pushing out adds no velocity, except a point
// that overlapped at the step's start (AllowXpbdStartOverlaps): that overlap
// leaves in position alone, so its parting is what earlier sub-steps' pushes
// left and goes to 0. v~_n is taken from the predicted velocities here, for
// the points that pushed only.
// `struck` is set where the approach was faster than the threshold.
double TargetNormalVelocity(const XpbdPoint& p, const XpbdPose& a, const XpbdPose& b, double threshold,
                            bool* struck) {
  const double vn_before = XpbdNormalVelocity(p, a.v, a.w, b.v, b.w);
  if (vn_before >= 0.0) return p.slack0 > 0.0 ? 0.0 : vn_before;
  if (-vn_before <= threshold) return 0.0;
  *struck = true;
  return -p.restitution * vn_before;
}

// The bodies of a block and their predicted states.
struct BlockBodies {
  SoftBody& A;
  SoftBody& B;
  const XpbdPose& a;
  const XpbdPose& b;
};

// The points of a block that pushed in the sub-step (lambda_n > 0): their
// places in the block and the sum of their multipliers.
struct PushedPoints {
  int idx[kMaxNormalBlock];
  int count = 0;
  double sum = 0.0;
};

// Restitution of a block's points that pushed, all at once through the
// inverse of their K (K^+ for a face's four), so the corners of a face
// share it whatever their order (their impulses summed before they reach
// the bodies); point by point where no block applies. Returns the largest
// change of a point's normal velocity it asked for (m/s), adds the normal
// impulses it applied to `normal_impulse` (N s) and sets `struck` where a
// point's approach was an impact (faster than the threshold).
double SolveBlockRestitution(double threshold, const NormalBlock& m, const PushedPoints& pushed_points,
                             XpbdSubsetCache& cache, const XpbdArticulation& articulation,
                             std::vector<SoftBody>& all, const BlockBodies& pair, std::vector<XpbdPoint>& points,
                             double* normal_impulse, bool* struck) {
  SoftBody& A = pair.A;
  SoftBody& B = pair.B;
  const int* idx = pushed_points.idx;
  const int pushed = pushed_points.count;
  const Eigen::Matrix4d* inv = nullptr;
  const XpbdPoint& p0 = points[m.first];
  // a lone point's K^-1 is 1 / w_n: the same number as through the cache
  // and the 4 x 4 product (whose other terms are zeros), at a fraction
  const bool lone = m.count == 1 && p0.w_n > 0.0;
  double largest = 0.0;
  if (lone || (inv = XpbdSubsetInverse(points, all, m, idx, pushed, cache)) != nullptr) {
    Eigen::Vector4d change = Eigen::Vector4d::Zero();
    for (int k = 0; k < pushed; ++k) {
      const XpbdPoint& p = points[m.first + idx[k]];
      change[k] = TargetNormalVelocity(p, pair.a, pair.b, threshold, struck) - NormalVelocity(p, A, B);
      largest = std::max(largest, std::abs(change[k]));
    }
    Eigen::Vector4d dl = Eigen::Vector4d::Zero();
    if (lone) {
      dl[0] = (1.0 / p0.w_n) * change[0];
    } else {
      dl.noalias() = *inv * change;
    }
    Vec3 J = Vec3::Zero(), wa = Vec3::Zero(), wb = Vec3::Zero();
    *normal_impulse += dl.sum();
    for (int k = 0; k < pushed; ++k) {
      XpbdPoint& p = points[m.first + idx[k]];
      const Vec3 Jk = dl[k] * p.n;
      p.impulse += Jk;
      J += Jk;
      // the torques of the impulses where the articulation takes them
      wa += dl[k] * (p0.jointed ? p.ra_n : p.ia_n);
      wb += dl[k] * (p0.jointed ? p.rb_n : p.ib_n);
    }
    if (p0.jointed) {
      articulation.Kick(all, p0.a, -J, -wa);
      articulation.Kick(all, p0.b, J, wb);
      return largest;
    }
    if (A.inv_mass > 0.0) {
      A.v -= A.inv_mass * J;
      A.w -= wa;
    }
    if (B.inv_mass > 0.0) {
      B.v += B.inv_mass * J;
      B.w += wb;
    }
    return largest;
  }
  for (int k = 0; k < pushed; ++k) {
    XpbdPoint& p = points[m.first + idx[k]];
    if (p.w_n <= 0.0) continue;
    const double change = TargetNormalVelocity(p, pair.a, pair.b, threshold, struck) - NormalVelocity(p, A, B);
    largest = std::max(largest, std::abs(change));
    const double dl = change / p.w_n;
    *normal_impulse += dl;
    p.impulse += dl * p.n;
    if (p.jointed) {
      articulation.Kick(all, p.a, -dl * p.n, -dl * p.ra_n);
      articulation.Kick(all, p.b, dl * p.n, dl * p.rb_n);
      continue;
    }
    PushImpulse(dl, p.n, p.ia_n, p.ib_n, A, B);
  }
  return largest;
}

}  // namespace

double SolveXpbdContactVelocities(double h, double restitution_threshold, const std::vector<NormalBlock>& blocks,
                                const std::vector<char>& deferred, int begin, int end, XpbdVelocitySweep sweep,
                                const std::vector<XpbdPatch>& patches,
                                std::vector<XpbdSubsetCache>& caches, const std::vector<XpbdPose>& predicted,
                                const XpbdArticulation& articulation, std::vector<SoftBody>& bodies,
                                std::vector<XpbdPassBlock>* blocks_state, std::vector<XpbdPoint>* points) {
  const double inv_h = 1.0 / h;
  double largest = 0.0;
  for (int k = begin; k < end; ++k) {
    const NormalBlock& m = blocks[k];
    PushedPoints pushed;
    for (int i = 0; i < m.count; ++i) {
      const double lambda = (*points)[m.first + i].lambda_n;
      if (lambda > 0.0) {
        pushed.idx[pushed.count++] = i;
        pushed.sum += lambda;
      }
    }
    const XpbdPatch& patch = patches[k];
    if (pushed.count == 0) {
      if (sweep.report) ReportXpbdSubstepImpulses(h, blocks, k, k + 1, patches, *blocks_state, points);
      continue;
    }
    const XpbdPoint& p0 = (*points)[m.first];
    // a jointed body's v~ as its joints leave it (XpbdArticulation::Projected)
    XpbdPose a = predicted[p0.a], b = predicted[p0.b];
    for (auto [i, pose] : {std::pair<int, XpbdPose*>{p0.a, &a}, {p0.b, &b}}) {
      if (!p0.jointed || !articulation.Jointed(i)) continue;
      const Vec6 v = articulation.Projected(i, predicted, bodies);
      pose->v = v.head<3>();
      pose->w = v.tail<3>();
    }
    const BlockBodies pair{bodies[p0.a], bodies[p0.b], a, b};
    // the brake's torque about the centres of mass (its impulse acts in the
    // contact plane, below a resting box's centre) turns the bodies, which
    // the normal rows then undo, and undoing it moves the patch's centre
    // again, which a second brake within the same limits stops: braked
    // after the normals only, a box sliding down a slope kept a pitch of
    // 0.010-0.016 rad/s (16 to 10 sub-steps); braked before them only, a
    // box held on a slope crept 4.3 mm in 2 s. The brakes accumulate over
    // the pass's sweeps, their sum within the limits (BrakeXpbdPatch).
    XpbdPassBlock& state = (*blocks_state)[k];
    if (sweep.first) {
      state.braked.setZero();
      state.spent.setZero();
      state.restitution = 0.0;
      // a patch held at its cone in positions has spent that friction
      // already (XpbdPatch::clamped): the brakes stay within the limit with it
      if (patch.clamped) {
        state.spent = Vec3(patch.t1.dot(patch.lambda_t), patch.t2.dot(patch.lambda_t), 0.0) * inv_h;
      }
    }
    // The brakes' Coulomb limit is mu times the sub-step's whole normal
    // impulse: the pushes' lambda_n / h and what the restitution added. A
    // landing's approach is mostly taken by the restitution (the push takes
    // only the overlap the last sub-step made), and braked by the pushes
    // alone a cube landing on a 40 degree slope with mu 0.9 kept 99% of its
    // tangential speed and slid 0.9 mm on, where rigid impacts stop it.
    const auto brake = [&] {
      const double normal = pushed.sum + h * std::max(state.restitution, 0.0);
      BrakeXpbdPatch(h, normal, patch, *points, p0.n, articulation, bodies, &state.spent, &state.braked);
    };
    const Vec3 braked_before = state.braked;
    brake();
    double change = 0.0;
    bool struck = false;
    if (!deferred[k]) {
      change = SolveBlockRestitution(restitution_threshold, m, pushed, caches[k], articulation, bodies, pair,
                                     *points, &state.restitution, &struck);
    }
    brake();
    // at an impact the brake's turn moves the normals again, so they take
    // their targets once more: without it the landing cube pitched and
    // bounced off its downhill edge
    if (struck) {
      change = std::max(change, SolveBlockRestitution(restitution_threshold, m, pushed, caches[k], articulation,
                                                      bodies, pair, *points, &state.restitution, &struck));
    }
    // the brakes' change of the patch's sliding velocity (its linear part)
    change = std::max(change, (state.braked - braked_before).norm() * p0.k_lin);
    largest = std::max(largest, change);
    if (sweep.report) ReportXpbdSubstepImpulses(h, blocks, k, k + 1, patches, *blocks_state, points);
  }
  return largest;
}

void ReportXpbdSubstepImpulses(double h, const std::vector<NormalBlock>& blocks, int begin, int end,
                               const std::vector<XpbdPatch>& patches, const std::vector<XpbdPassBlock>& brakes,
                               std::vector<XpbdPoint>* points) {
  // a point's push lambda_n moved the bodies as the velocity impulse
  // lambda_n / h does, and the patch's friction (its positional multiplier
  // / h and the brakes) is shared by the points' pushes
  const double inv_h = 1.0 / h;
  for (int k = begin; k < end; ++k) {
    const NormalBlock& m = blocks[k];
    const XpbdPatch& patch = patches[k];
    double sum = 0.0;
    for (int i = m.first; i < m.first + m.count; ++i) sum += std::max((*points)[i].lambda_n, 0.0);
    if (sum == 0.0) {
      // static friction acted while the points pushed, and the direct
      // solve of a heavy-on-light component has since let them go
      if (!patch.lambda_t.isZero(0.0)) (*points)[m.first].impulse += patch.lambda_t * inv_h;
      continue;
    }
    const Vec3& n = (*points)[m.first].n;
    const Vec3 friction = (patch.lambda_t * inv_h + brakes[k].braked) / sum;
    for (int i = m.first; i < m.first + m.count; ++i) {
      XpbdPoint& p = (*points)[i];
      if (p.lambda_n > 0.0) p.impulse += (p.lambda_n * inv_h) * n + p.lambda_n * friction;
    }
  }
}

}  // namespace contactsim
