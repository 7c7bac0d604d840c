#include "service/contact/xpbd/xpbd_patch_friction.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

namespace contactsim {
namespace {

// K of a jointed patch's rows (t1, t2, twist) through the bodies' mobility.
Eigen::Matrix3d JointedPatchK(const XpbdPatch& patch, const Vec3& n, const XpbdArticulation& articulation,
                              const XpbdPoint& p0, const SoftBody& A, const SoftBody& B) {
  const Vec3 lin[3] = {patch.t1, patch.t2, Vec3::Zero()};
  const Vec3 ang_a[3] = {patch.ra.cross(patch.t1), patch.ra.cross(patch.t2), n};
  const Vec3 ang_b[3] = {patch.rb.cross(patch.t1), patch.rb.cross(patch.t2), n};
  Eigen::Matrix3d k;
  for (int j = 0; j < 3; ++j) {
    const Vec6 resp_a = articulation.Response(p0.a, A, lin[j], ang_a[j]);
    const Vec6 resp_b = articulation.Response(p0.b, B, lin[j], ang_b[j]);
    for (int i = 0; i < 3; ++i) {
      k(i, j) = lin[i].dot(resp_a.head<3>() + resp_b.head<3>()) + ang_a[i].dot(resp_a.tail<3>()) +
                ang_b[i].dot(resp_b.tail<3>());
    }
  }
  return 0.5 * (k + k.transpose());
}

// K of the rows t1, t2 (at the patch centre) and the twist about n.
Eigen::Matrix3d PatchK(const XpbdPatch& patch, const Vec3& n, const SoftBody& A, const SoftBody& B) {
  const Vec3 lin[3] = {patch.t1, patch.t2, Vec3::Zero()};
  const Vec3 ang_a[3] = {patch.ra.cross(patch.t1), patch.ra.cross(patch.t2), n};
  const Vec3 ang_b[3] = {patch.rb.cross(patch.t1), patch.rb.cross(patch.t2), n};
  Vec3 resp_a[3], resp_b[3];  // I^-1 of each row's angular part, once a column
  for (int j = 0; j < 3; ++j) {
    resp_a[j] = A.inv_inertia * ang_a[j];
    resp_b[j] = B.inv_inertia * ang_b[j];
  }
  Eigen::Matrix3d k;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      k(i, j) = (A.inv_mass + B.inv_mass) * lin[i].dot(lin[j]) + ang_a[i].dot(resp_a[j]) + ang_b[i].dot(resp_b[j]);
    }
  }
  return k;
}

bool InvertPatchK(const Eigen::Matrix3d& k, int rows, Eigen::Matrix3d* inv) {
  inv->setZero();
  if (rows == 2) {
    const Eigen::Matrix2d k2 = k.topLeftCorner<2, 2>();
    if (!(k2.determinant() > 1e-12 * k2.trace() * k2.trace())) return false;
    inv->topLeftCorner<2, 2>() = k2.inverse();
    return true;
  }
  const Eigen::LLT<Eigen::Matrix3d> llt(k);
  if (llt.info() != Eigen::Success) return false;
  const Vec3 d = llt.matrixLLT().diagonal();
  if (!(d.minCoeff() > 1e-6 * d.maxCoeff())) return false;
  // K^-1 = L^-T L^-1 from the factor by substitution (llt.solve of the
  // identity went through Eigen's general triangular solver, the larger part
  // of preparing a patch)
  const Eigen::Matrix3d L = llt.matrixL();
  Eigen::Matrix3d inv_l = Eigen::Matrix3d::Zero();
  for (int j = 0; j < 3; ++j) {
    inv_l(j, j) = 1.0 / L(j, j);
    for (int i = j + 1; i < 3; ++i) {
      double sum = 0.0;
      for (int m = j; m < i; ++m) sum += L(i, m) * inv_l(m, j);
      inv_l(i, j) = -sum / L(i, i);
    }
  }
  inv->noalias() = inv_l.transpose() * inv_l;
  return true;
}

}  // namespace

void PrepareXpbdPatches(const std::vector<NormalBlock>& blocks, const std::vector<XpbdPoint>& points,
                        const std::vector<XpbdPointFrame>& frames, const std::vector<SoftBody>& bodies,
                        const XpbdArticulation& articulation, PatchTorsion torsion,
                        std::vector<XpbdPatch>* patches) {
  patches->resize(blocks.size());
  for (size_t k = 0; k < blocks.size(); ++k) {
    XpbdPatch patch;
    patch.first = blocks[k].first;
    patch.count = blocks[k].count;
    const XpbdPoint& p0 = points[patch.first];
    const XpbdPointFrame& f0 = frames[patch.first];
    PerpendicularBasis(p0.n, &patch.t1, &patch.t2);
    patch.friction = f0.friction;
    for (int i = 0; i < patch.count; ++i) {
      patch.ra += points[patch.first + i].ra / patch.count;
      patch.mean_a += frames[patch.first + i].material_a / patch.count;
      patch.mean_b += frames[patch.first + i].material_b / patch.count;
    }
    patch.rb = patch.ra + (f0.rb - p0.ra);
    double place[kMaxNormalBlock][2];
    for (int i = 0; i < patch.count; ++i) {
      const Vec3 d = points[patch.first + i].ra - patch.ra;
      place[i][0] = d.dot(patch.t1);
      place[i][1] = d.dot(patch.t2);
      const double r2 = place[i][0] * place[i][0] + place[i][1] * place[i][1];
      patch.spread += r2;
      patch.twist_radius += std::sqrt(r2) / patch.count;
    }
    const int rows = patch.twist_radius > 1e-6 ? 3 : 2;
    if (rows == 2) patch.twist_radius = patch.spread = 0.0;
    if (rows == 3 && torsion == PatchTorsion::kUniform) {
      Vec3 arms[kMaxNormalBlock], centre;
      for (int i = 0; i < patch.count; ++i) arms[i] = points[patch.first + i].ra;
      const double r_eff = UniformPatchRadius(arms, patch.count, p0.n, &centre);
      if (r_eff > 0.0) {
        patch.lever_scale = r_eff / patch.twist_radius;
        patch.twist_radius = r_eff;
      }
    }
    for (int i = 0; rows == 3 && i < patch.count; ++i) {
      for (int j = 0; j < 2; ++j) {
        const double w = place[i][j] / patch.spread;
        patch.twist_a[j] += w * frames[patch.first + i].material_a;
        patch.twist_b[j] += w * frames[patch.first + i].material_b;
        patch.twist_c[j] += w;
      }
    }
    const SoftBody& A = bodies[p0.a];
    const SoftBody& B = bodies[p0.b];
    patch.jointed = p0.jointed;
    patch.k = patch.jointed ? JointedPatchK(patch, p0.n, articulation, p0, A, B) : PatchK(patch, p0.n, A, B);
    patch.valid = patch.friction > 0.0 && InvertPatchK(patch.k, rows, &patch.inv_k);
    (*patches)[k] = patch;
  }
}

void RefreshJointedXpbdPatch(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies,
                             const XpbdArticulation& articulation, XpbdPatch* patch) {
  const XpbdPoint& p0 = points[patch->first];
  const int rows = patch->twist_radius > 0.0 ? 3 : 2;
  const Eigen::Matrix3d K = JointedPatchK(*patch, p0.n, articulation, p0, bodies[p0.a], bodies[p0.b]);
  patch->valid = patch->friction > 0.0 && InvertPatchK(K, rows, &patch->inv_k);
}

void BeginXpbdPatch(XpbdPatch* patch) {
  if (patch->sticking && !patch->jointed && !patch->compound) {
    patch->step_lambda_t += patch->lambda_t;
    patch->step_pushed += patch->pushed;
  } else {
    patch->step_lambda_t.setZero();
    patch->step_pushed = 0.0;
  }
  patch->pushed = 0.0;
  patch->lambda_t.setZero();
  patch->lambda_twist = 0.0;
  patch->clamped = false;
}

namespace {

// The patch's offset now, in the tangent frame: the mean of its points'
// tangential offsets o_i = t . ((x_A + R_A m_Ai) - (x_B + R_B m_Bi)) along
// (t1, t2), and their twist about n, sum_i (d_i1 o_i2 - d_i2 o_i1) / spread.
// Both are linear in the m_i, so they come from the patch's sums with the
// tangents turned into each body's frame, t . R m = (R^T t) . m.
// The bodies' poses are (xa, q_a) and (xb, q_b).
Vec3 PatchOffset(const XpbdPatch& patch, const Vec3& xa, const Quat& q_a, const Vec3& xb, const Quat& q_b) {
  if (patch.count == 1) {  // one point: turning its two points is cheaper than the four tangents
    const Vec3 d = (xa + q_a * patch.mean_a) - (xb + q_b * patch.mean_b);
    return Vec3(patch.t1.dot(d), patch.t2.dot(d), 0.0);
  }
  const Quat qa = q_a.conjugate(), qb = q_b.conjugate();
  const Vec3 at1 = qa * patch.t1, at2 = qa * patch.t2, bt1 = qb * patch.t1, bt2 = qb * patch.t2;
  const Vec3 centres = xa - xb;
  const double c1 = patch.t1.dot(centres), c2 = patch.t2.dot(centres);
  const double u1 = c1 + at1.dot(patch.mean_a) - bt1.dot(patch.mean_b);
  const double u2 = c2 + at2.dot(patch.mean_a) - bt2.dot(patch.mean_b);
  if (patch.spread == 0.0) return Vec3(u1, u2, 0.0);
  const double twist = (c2 * patch.twist_c[0] + at2.dot(patch.twist_a[0]) - bt2.dot(patch.twist_b[0])) -
                       (c1 * patch.twist_c[1] + at1.dot(patch.twist_a[1]) - bt1.dot(patch.twist_b[1]));
  return Vec3(u1, u2, twist);
}

}  // namespace

Vec3 XpbdPatchError(const World& world, const XpbdPatch& patch, const std::vector<XpbdPoint>& points) {
  const XpbdPoint& p0 = points[patch.first];
  const RigidBody& A = world.bodies()[p0.a];
  const RigidBody& B = world.bodies()[p0.b];
  return PatchOffset(patch, A.x, A.q, B.x, B.q) - patch.origin;
}

bool XpbdPatchSlipNow(const World& world, const XpbdPatch& patch, const std::vector<XpbdPoint>& points,
                      XpbdPatchSlip* slip) {
  if (!patch.valid || patch.origin_pending || !patch.sticking) return false;
  const XpbdPoint& p0 = points[patch.first];
  const RigidBody& A = world.bodies()[p0.a];
  const RigidBody& B = world.bodies()[p0.b];
  const Vec3 d = PatchOffset(patch, A.x, A.q, B.x, B.q) - patch.origin;
  slip->along = d[0] * patch.t1 + d[1] * patch.t2;
  slip->twist = d[2];
  return true;
}

void CarryXpbdPatchSlip(const XpbdPatchSlip& slip, XpbdPatch* patch) {
  patch->origin = -Vec3(patch->t1.dot(slip.along), patch->t2.dot(slip.along),
                        patch->twist_radius > 0.0 ? slip.twist : 0.0);
}

void SolveXpbdPatchFriction(World& world, const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
                            const NormalBlock& block, XpbdSubsetCache& cache, XpbdPatch& patch,
                            std::vector<XpbdPoint>& points) {
  if (!patch.valid) return;
  const XpbdPoint& p0 = points[patch.first];
  double pushed = 0.0;
  for (int i = 0; i < patch.count; ++i) pushed += points[patch.first + i].lambda_n;
  const RigidBody& A = world.bodies()[p0.a];
  const RigidBody& B = world.bodies()[p0.b];
  patch.sticking = false;
  if (pushed <= 0.0) {  // not touching: hold the present offset from now on
    patch.origin_pending = true;
    patch.hold_xa = A.x;
    patch.hold_qa = A.q;
    patch.hold_xb = B.x;
    patch.hold_qb = B.q;
    return;
  }
  if (patch.origin_pending) {
    patch.origin = PatchOffset(patch, patch.hold_xa, patch.hold_qa, patch.hold_xb, patch.hold_qb);
    patch.origin_pending = false;
  }
  const Vec3 offset = PatchOffset(patch, A.x, A.q, B.x, B.q);
  const Vec3 r = offset - patch.origin;
  if (!patch.jointed && !patch.compound &&
      SolveHeldXpbdPatchFriction(world, bodies, block, cache, r, offset, pushed, patch, points)) {
    return;
  }
  Vec3 dl = patch.inv_k * r;
  const double mu = patch.friction;
  if (patch.compound && patch.twist_radius > 0.0 &&
      std::abs(patch.lambda_twist + dl[2]) > mu * pushed * patch.twist_radius) {
    // The twist is let go below (it spins), so the tangent rows are solved
    // without it, by the inverse of K's tangent block: the Schur complement
    // G_tt - G_tw G_wt / G_ww of G = K^-1. The joint solution's tangent part
    // counts on the twist's turn to move the patch centre, which matters
    // where the patch lies off the centre of mass's vertical (a table's
    // leg): applied without the twist it turned the body instead, and a
    // resting table kept rocking among its legs at 1.4e-3 m/s.
    const Eigen::Matrix3d& g = patch.inv_k;
    const Eigen::Vector2d tw = g.block<2, 1>(0, 2);
    const Eigen::Matrix2d g_tt = g.topLeftCorner<2, 2>() - tw * tw.transpose() / g(2, 2);
    dl.head<2>() = g_tt * r.head<2>();
  }
  Vec3 lambda_t = patch.lambda_t + dl[0] * patch.t1 + dl[1] * patch.t2;
  double twist_step = dl[2];
  // the cone over the step for a patch of free bodies (header); the step's
  // sums stay zero for a jointed or compound patch
  if ((patch.step_lambda_t + lambda_t).norm() > mu * (patch.step_pushed + pushed)) {  // the patch slides
    if (!patch.jointed) {
      patch.origin = offset;
      return;
    }
    // a jointed patch keeps its offset and takes the cone's most (header)
    lambda_t *= mu * pushed / lambda_t.norm();
    twist_step = 0.0;
    patch.clamped = true;
  } else {
    patch.sticking = true;
  }
  if (std::abs(patch.lambda_twist + twist_step) > mu * pushed * patch.twist_radius) {
    patch.origin[2] = offset[2];  // it spins: hold the translation only
    twist_step = 0.0;
  }
  const Vec3 P = lambda_t - patch.lambda_t;
  const Vec3& n = p0.n;
  patch.lambda_t = lambda_t;
  patch.pushed = pushed;
  patch.lambda_twist += twist_step;
  if (patch.jointed) {
    articulation.Displace(world, bodies, p0.a, -P, -(patch.ra.cross(P) + twist_step * n));
    articulation.Displace(world, bodies, p0.b, P, patch.rb.cross(P) + twist_step * n);
    return;
  }
  const SoftBody& sa = bodies[p0.a];
  const SoftBody& sb = bodies[p0.b];
  DisplaceXpbdBody(world.bodies()[p0.a], sa, -sa.inv_mass * P, -(sa.inv_inertia * (patch.ra.cross(P) + twist_step * n)));
  DisplaceXpbdBody(world.bodies()[p0.b], sb, sb.inv_mass * P, sb.inv_inertia * (patch.rb.cross(P) + twist_step * n));
}

namespace {

// The friction impulse (t1, t2, twist about n) on B of the patch's points
// sliding with the patch's slip (v1, v2) at its centre and its spin about
// n: each point's Coulomb disk at its rim, against its own slip
// u_i = v + spin n x d_i (Moreau's maximal dissipation, point by point).
Vec3 PointsSlidingImpulse(double h, const XpbdPatch& patch, const std::vector<XpbdPoint>& points, double v1,
                          double v2, double spin) {
  Vec3 total = Vec3::Zero();
  for (int i = 0; i < patch.count; ++i) {
    const XpbdPoint& p = points[patch.first + i];
    if (!(p.lambda_n > 0.0)) continue;
    const Vec3 d = p.ra - patch.ra;
    const double d1 = patch.lever_scale * patch.t1.dot(d), d2 = patch.lever_scale * patch.t2.dot(d);
    const double u1 = v1 - spin * d2, u2 = v2 + spin * d1;
    const double speed = std::sqrt(u1 * u1 + u2 * u2);
    if (!(speed > 0.0)) continue;
    const double f = -patch.friction * p.lambda_n / (h * speed);
    total += Vec3(f * u1, f * u2, f * (d1 * u2 - d2 * u1));
  }
  return total;
}

// The sliding brake's change dl (t1, t2, twist) of a patch whose centre
// lies off its bodies' centres of mass, scaled into [0, 1] so that it
// stops no more than the slip (generalised, with the twist) along dl:
// alpha = -(dl . slip) / (dl^T K dl), 0 when dl does not oppose the slip.
// Taking the force and the torque each from whichever of the sliding and
// the stopping impulse is smaller, as for a patch under the centre of
// mass, mixes two impulses whose parts are coupled through K there (the
// twist of the stopping one carries the turn its force needs): on the legs
// of a table that sum pushed along the spin, and a resting table spun up
// about the vertical to 1.17 rad/s in 2 s.
Vec3 SlidingWithinStop(const XpbdPatch& patch, const Vec3& dl, const Vec3& slip) {
  const double power = dl.dot(slip);
  if (!(power < 0.0)) return Vec3::Zero();
  const Eigen::Matrix3d k = patch.inv_k.inverse();
  const double stiff = dl.dot(k * dl);
  return stiff > -power ? Vec3((-power / stiff) * dl) : dl;
}

}  // namespace

void BrakeXpbdPatch(double h, double pushed, const XpbdPatch& patch, const std::vector<XpbdPoint>& points,
                    const Vec3& n, const XpbdArticulation& articulation, std::vector<SoftBody>& bodies, Vec3* spent,
                    Vec3* applied) {
  if (!patch.valid) return;
  const XpbdPoint& p0 = points[patch.first];
  SoftBody& A = bodies[p0.a];
  SoftBody& B = bodies[p0.b];
  const Vec3 v = (B.v + B.w.cross(patch.rb)) - (A.v + A.w.cross(patch.ra));
  const Vec3 spin = B.w - A.w;
  const Vec3 slip(patch.t1.dot(v), patch.t2.dot(v), patch.twist_radius > 0.0 ? n.dot(spin) : 0.0);
  Vec3 total = *spent - patch.inv_k * slip;
  // Coulomb's disk for the patch's force, its torque within mu N r
  const double limit = patch.friction * pushed / h;
  // impulses of the patch's bodies: no overflow for hypot to guard against
  const double along = std::sqrt(total[0] * total[0] + total[1] * total[1]);
  const double twist_limit = limit * patch.twist_radius;
  if ((along > limit || std::abs(total[2]) > twist_limit) && patch.twist_radius > 0.0) {
    // it slides: the force and torque its points' friction gives for this
    // slip (separate limits on the two let a sliding face brake its spin
    // with the whole mu N r), stopping neither the slide nor the spin
    // beyond what the free brake above would
    const Vec3 sliding = PointsSlidingImpulse(h, patch, points, slip[0], slip[1], slip[2]);
    if (patch.compound) {
      total = *spent + SlidingWithinStop(patch, sliding - *spent, slip);
    } else {
      const double sliding_along = std::sqrt(sliding[0] * sliding[0] + sliding[1] * sliding[1]);
      if (sliding_along < along) total.head<2>() = sliding.head<2>();
      if (std::abs(sliding[2]) < std::abs(total[2])) total[2] = sliding[2];
    }
  } else if (along > limit) {
    total[0] *= limit / along;
    total[1] *= limit / along;
  }
  const Vec3 dl = total - *spent;
  *spent = total;
  const Vec3 J = dl[0] * patch.t1 + dl[1] * patch.t2;
  *applied += J;
  if (patch.jointed) {
    articulation.Kick(bodies, p0.a, -J, -(patch.ra.cross(J) + dl[2] * n));
    articulation.Kick(bodies, p0.b, J, patch.rb.cross(J) + dl[2] * n);
    return;
  }
  if (A.inv_mass > 0.0) {  // a static body is never written (PushNormal)
    A.v -= A.inv_mass * J;
    A.w -= A.inv_inertia * (patch.ra.cross(J) + dl[2] * n);
  }
  if (B.inv_mass > 0.0) {
    B.v += B.inv_mass * J;
    B.w += B.inv_inertia * (patch.rb.cross(J) + dl[2] * n);
  }
}

}  // namespace contactsim
