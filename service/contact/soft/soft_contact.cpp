#include "service/contact/soft/soft_contact.h"

#include <algorithm>
#include <cmath>

#include "service/contact/contact_row.h"
#include "service/contact/slip_friction_step.h"

namespace contactsim {
namespace {

// 1 / K, K = 1/m_A + 1/m_B + (r_A x d) . I_A^-1 (r_A x d) + ... (contact_row.h)
double MassOf(double k) { return k > 0.0 ? 1.0 / k : 0.0; }

// The relative normal speed at which the pair meets: for a pair apart by
// s_0 > 0 at the step's start, closing under constant accelerations a_n
// (the bodies' forces; gravity), v_impact^2 = v_n0^2 - 2 a_n s_0, as in free
// flight, so a ball dropped from h bounces to e^2 h whatever part of the step
// it lands in; a pair already touching meets at v_n0.
double ImpactSpeed(const SoftPoint& p, const World& world, double vn0, double s0) {
  if (s0 <= 0.0) return vn0;
  const RigidBody& A = world.bodies()[p.a];
  const RigidBody& B = world.bodies()[p.b];
  const double acc_a = A.IsDynamic() ? p.n.dot(A.force) * A.inv_mass : 0.0;
  const double acc_b = B.IsDynamic() ? p.n.dot(B.force) * B.inv_mass : 0.0;
  const double squared = vn0 * vn0 - 2.0 * (acc_b - acc_a) * s0;
  return -std::sqrt(std::max(squared, 0.0));
}

// contacts a thread prepares at a time
constexpr int kSoftPrepareGrain = 256;

// The friction rows' Jacobians, responses and masses of a point acting at
// fa, fb (lever arms from A's and B's centres of mass).
void SetFrictionRows(const Vec3& fa, const Vec3& fb, const SoftBody& sa, const SoftBody& sb, SoftPoint* p) {
  p->ra_t1 = fa.cross(p->t1), p->ra_t2 = fa.cross(p->t2);
  p->rb_t1 = fb.cross(p->t1), p->rb_t2 = fb.cross(p->t2);
  p->ia_t1 = sa.inv_inertia * p->ra_t1, p->ia_t2 = sa.inv_inertia * p->ra_t2;
  p->ib_t1 = sb.inv_inertia * p->rb_t1, p->ib_t2 = sb.inv_inertia * p->rb_t2;
  const double k_lin = sa.inv_mass + sb.inv_mass;
  p->mass_t1 = MassOf(k_lin + p->ra_t1.dot(p->ia_t1) + p->rb_t1.dot(p->ib_t1));
  p->mass_t2 = MassOf(k_lin + p->ra_t2.dot(p->ia_t2) + p->rb_t2.dot(p->ib_t2));
  p->k_t12 = p->ra_t1.dot(p->ia_t2) + p->rb_t1.dot(p->ib_t2);
}

// The normal row's Jacobians, responses and effective mass.
void SetNormalRow(const SoftBody& sa, const SoftBody& sb, SoftPoint* p) {
  p->ra_n = p->ra.cross(p->n), p->rb_n = p->rb.cross(p->n);
  p->ia_n = sa.inv_inertia * p->ra_n, p->ib_n = sb.inv_inertia * p->rb_n;
  p->mass_n = MassOf(sa.inv_mass + sb.inv_mass + p->ra_n.dot(p->ia_n) + p->rb_n.dot(p->ib_n));
}

}  // namespace

void PrepareSoftPoints(const ContactSet& contacts, const World& world, const std::vector<SoftBody>& bodies,
                       const std::vector<Vec3>* friction_points, const SoftSprings& springs, ParallelRunner& runner,
                       std::vector<SoftPoint>* points, bool rows) {
  // each point made over last step's in its slot: a point returned and
  // copied into its slot, or a default one made first, cost 0.25M and
  // 0.18M instructions more a float pyramid step (BENCHMARKS.md, "soft:
  // the float path")
  points->resize(contacts.size());
  runner.For(static_cast<int>(contacts.size()), kSoftPrepareGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      // the narrowphase emits a pair's points together, most with one normal
      const bool same_frame =
          k > begin && SharesContactFrame(contacts[k], contacts[k - 1].a, contacts[k - 1].b, contacts[k - 1].normal);
      PrepareSoftPoint(contacts[k], world, bodies, friction_points != nullptr ? &(*friction_points)[k] : nullptr,
                       springs, rows, same_frame ? &(*points)[k - 1] : nullptr, &(*points)[k]);
    }
  });
}

void PrepareSoftPoint(const Contact& c, const World& world, const std::vector<SoftBody>& bodies,
                      const Vec3* friction_point, const SoftSprings& springs, bool rows,
                      const SoftPoint* same_frame, SoftPoint* out) {
  const SoftBody& sa = bodies[c.a];
  const SoftBody& sb = bodies[c.b];
  SoftPoint& p = *out;
  if (same_frame != nullptr) {
    // MakeContactBasis's anchors; its tangents and materials are the same
    // functions of the same normal and bodies (taken once a manifold,
    // MakeContactBasis cost 0.07M instructions a float pyramid step
    // instead of 0.29M: BENCHMARKS.md, "soft: the float path")
    p.ra = c.point - world.bodies()[c.a].x;
    p.rb = c.point - world.bodies()[c.b].x;
    p.n = c.normal;
    p.t1 = same_frame->t1;
    p.t2 = same_frame->t2;
    p.friction = same_frame->friction;
    p.restitution = same_frame->restitution;
  } else {
    const ContactRow basis = MakeContactBasis(c, world);
    p.ra = basis.ra;
    p.rb = basis.rb;
    p.n = basis.n;
    p.t1 = basis.t1;
    p.t2 = basis.t2;
    p.friction = basis.friction;
    p.restitution = basis.restitution;
  }
  p.a = c.a;
  p.b = c.b;
  if (rows) {
    SetNormalRow(sa, sb, &p);
    // where the friction acts: the contact point, or one of the patch's (patch_torsion.h)
    const Vec3 fa = friction_point != nullptr ? Vec3(*friction_point - world.bodies()[c.a].x) : p.ra;
    const Vec3 fb = friction_point != nullptr ? Vec3(*friction_point - world.bodies()[c.b].x) : p.rb;
    SetFrictionRows(fa, fb, sa, sb, &p);
  } else {
    p.mass_n = p.mass_t1 = p.mass_t2 = p.k_t12 = 0.0;
  }
  // the step's impulses start from nothing (the warm start sets lambda after)
  p.lambda_n = p.lambda_t1 = p.lambda_t2 = 0.0;
  p.max_push = p.total_n = p.total_t1 = p.total_t2 = 0.0;
  p.soft = world.bodies()[c.a].IsDynamic() && world.bodies()[c.b].IsDynamic() ? springs.movable : springs.fixed;
  p.adjusted_separation = -c.depth - p.n.dot(p.rb - p.ra);
  p.impact_speed = ImpactSpeed(p, world, p.NormalVelocity(sa, sb), -c.depth);
}

void SoftFrictionArms(const SoftPoint& p, int k, const std::vector<Vec3>* friction_points,
                      const std::vector<SoftBody>& bodies, Vec3* fa, Vec3* fb) {
  if (friction_points == nullptr) {
    *fa = p.ra, *fb = p.rb;
    return;
  }
  *fa = (*friction_points)[k] - bodies[p.a].x0;
  *fb = (*friction_points)[k] - bodies[p.b].x0;
}

void PrepareSoftRows(const std::vector<SoftBody>& bodies, const std::vector<Vec3>* friction_points,
                     ParallelRunner& runner, std::vector<SoftPoint>* points, bool friction_rows) {
  runner.For(static_cast<int>(points->size()), kSoftPrepareGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      SoftPoint& p = (*points)[k];
      SetNormalRow(bodies[p.a], bodies[p.b], &p);
      if (!friction_rows) continue;
      Vec3 fa, fb;
      SoftFrictionArms(p, k, friction_points, bodies, &fa, &fb);
      SetFrictionRows(fa, fb, bodies[p.a], bodies[p.b], &p);
    }
  });
}

void SoftPointsOfBodies::Build(const std::vector<SoftPoint>& points, const std::vector<SoftBody>& bodies,
                               const std::vector<int>* point_of_contact) {
  start.assign(bodies.size() + 1, 0);
  for (const SoftPoint& p : points) {
    for (int i : {p.a, p.b}) start[i + 1] += bodies[i].inv_mass > 0.0 ? 1 : 0;
  }
  for (size_t i = 0; i < bodies.size(); ++i) start[i + 1] += start[i];
  entries.resize(start.back());
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int c = 0; c < static_cast<int>(points.size()); ++c) {
    const int k = point_of_contact != nullptr ? (*point_of_contact)[c] : c;
    if (bodies[points[k].a].inv_mass > 0.0) entries[next[points[k].a]++] = 2 * k;
    if (bodies[points[k].b].inv_mass > 0.0) entries[next[points[k].b]++] = 2 * k + 1;
  }
}

void WarmStartSoftBody(int i, const SoftPointsOfBodies& list, const std::vector<SoftPoint>& points,
                       std::vector<SoftBody>& bodies) {
  SoftBody& body = bodies[i];
  // the terms of SoftPoint::Push in its order, n, t1, t2, with B's sign
  for (int e = list.start[i]; e < list.start[i + 1]; ++e) {
    const SoftPoint& p = points[list.entries[e] >> 1];
    if ((list.entries[e] & 1) != 0) {
      body.v += (body.inv_mass * p.lambda_n) * p.n;
      body.w += p.lambda_n * p.ib_n;
      body.v += (body.inv_mass * p.lambda_t1) * p.t1;
      body.w += p.lambda_t1 * p.ib_t1;
      body.v += (body.inv_mass * p.lambda_t2) * p.t2;
      body.w += p.lambda_t2 * p.ib_t2;
    } else {
      body.v -= (body.inv_mass * p.lambda_n) * p.n;
      body.w -= p.lambda_n * p.ia_n;
      body.v -= (body.inv_mass * p.lambda_t1) * p.t1;
      body.w -= p.lambda_t1 * p.ia_t1;
      body.v -= (body.inv_mass * p.lambda_t2) * p.t2;
      body.w -= p.lambda_t2 * p.ia_t2;
    }
  }
}

SoftRowTarget SoftNormalTarget(const SoftPass& pass, const SoftPoint& p, double s) {
  SoftRowTarget t;
  if (s > 0.0) {
    // speculative: may close the gap, not pass it; in the relax pass a point
    // that pushes keeps its gap (see soft_contact.h)
    t.bias = pass.hold_pushing_gaps && p.lambda_n > 0.0 ? 0.0 : s * pass.inv_h;
  } else if (pass.use_bias) {
    t.bias = std::max(p.soft.bias_rate * s, -pass.max_push_velocity);
    t.mass_scale = p.soft.mass_scale;
    t.impulse_scale = p.soft.impulse_scale;
  }
  return t;
}

double SoftSeparation(const SoftPoint& p, const SoftBody& A, const SoftBody& B) {
  const Vec3 d = (B.dp - A.dp) + (B.dR * p.rb - A.dR * p.ra);
  return p.n.dot(d) + p.adjusted_separation;
}

void ApplySoftNormal(double total, SoftPoint& p, SoftBody& A, SoftBody& B) {
  const double applied = total - p.lambda_n;
  p.lambda_n = total;
  p.max_push = std::max(p.max_push, applied);
  SoftPoint::Push(applied, p.n, p.ia_n, p.ib_n, A, B);
}

void SolveSoftNormal(const SoftPass& pass, SoftPoint& p, SoftBody& A, SoftBody& B) {
  const SoftRowTarget t = SoftNormalTarget(pass, p, SoftSeparation(p, A, B));
  const double vn = p.VelocityAlong(p.n, p.ra_n, p.rb_n, A, B);
  const double increment = -p.mass_n * t.mass_scale * (vn + t.bias) - t.impulse_scale * p.lambda_n;
  ApplySoftNormal(std::max(p.lambda_n + increment, 0.0), p, A, B);
}

void SolveSoftFriction(SoftPoint& p, SoftBody& A, SoftBody& B) {
  // both tangents from one relative velocity, one update of each body
  const Vec3 dv = B.v - A.v;
  const double u1 = p.t1.dot(dv) + p.rb_t1.dot(B.w) - p.ra_t1.dot(A.w);
  const double u2 = p.t2.dot(dv) + p.rb_t2.dot(B.w) - p.ra_t2.dot(A.w);
  double l1 = p.lambda_t1, l2 = p.lambda_t2;
  SlipFrictionStep(p.friction * p.lambda_n, u1, u2, p.mass_t1, p.mass_t2, p.k_t12, &l1, &l2);
  const double d1 = l1 - p.lambda_t1, d2 = l2 - p.lambda_t2;
  p.lambda_t1 = l1;
  p.lambda_t2 = l2;
  const Vec3 J = d1 * p.t1 + d2 * p.t2;
  if (A.inv_mass > 0.0) {
    A.v -= A.inv_mass * J;
    A.w -= d1 * p.ia_t1 + d2 * p.ia_t2;
  }
  if (B.inv_mass > 0.0) {
    B.v += B.inv_mass * J;
    B.w += d1 * p.ib_t1 + d2 * p.ib_t2;
  }
}

void AccumulateSoftTotals(SoftPoint& p) {
  p.total_n += p.lambda_n;
  p.total_t1 += p.lambda_t1;
  p.total_t2 += p.lambda_t2;
}

}  // namespace contactsim
