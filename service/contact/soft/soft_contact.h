// Contact points of the soft step (soft_method.h) and the passes over them.
//
// Each point keeps its anchors r_A, r_B (contact point minus centre of mass,
// world, at the step's start), its normal and contact-frame tangents
// (PerpendicularBasis, so warm starts carry over), and the effective masses
// 1 / K along n, t1, t2 (contact_row.h). Its separation during the step is
// brought up to date from the bodies' motion since the step began:
//   s = n . ((dp_B + dR_B r_B) - (dp_A + dR_A r_A)) + s_0 - n . (r_B - r_A),
// exact for translation and first order in the turn, so the narrowphase runs
// once per step (Catto, Solver2D "Soft Step", 2024).
//
// The normal row, with v_n the relative normal velocity at the anchors:
//   s > 0 (apart):  speculative, v_n >= -s / h: a body may close the gap
//                   within the sub-step but not pass it (rigid);
//   s <= 0, bias:   a soft spring (softness.h), pushing out at most
//                   max_push_velocity;
//   s <= 0, relax:  rigid, v_n >= 0, no push (removes the spring's velocity,
//                   so pushing out adds no energy);
//   s > 0, relax, lambda_n > 0 (SoftPass::hold_pushing_gaps): rigid,
//                   v_n >= 0: a point that pushes keeps
//                   the gap it rests at. Where a face's other points sink
//                   into their springs, the solve pass holds one point a
//                   hair apart (0.9 um) under load; letting the relax pass
//                   close that gap at s / h tipped a resting hull at
//                   1e-3 m/s, a velocity the next solve took back (the body
//                   did not move) but the step reported.
// Accumulated impulses are clamped at 0 (Catto 2005). Friction is Coulomb's
// disk: both tangent impulses from the same relative velocity, their sum
// projected onto |lambda_t| <= mu lambda_n. Restitution comes after the
// sub-steps (soft_restitution.h).
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/collision/parallel_runner.h"
#include "service/contact/push_impulse.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/soft/softness.h"

namespace contactsim {

struct SoftPoint {
  int a = -1, b = -1;
  Vec3 ra = Vec3::Zero(), rb = Vec3::Zero();  // m, anchors at the step's start
  Vec3 n = Vec3::UnitZ(), t1 = Vec3::UnitX(), t2 = Vec3::UnitY();  // unit, world; n from A to B
  // the rows' angular Jacobians r x d and responses I^-1 (r x d) for
  // d = n, t1, t2, at the step's start (the solve keeps them for the step);
  // the friction rows' r is where the point's friction acts (patch_torsion.h)
  Vec3 ra_n, ra_t1, ra_t2, rb_n, rb_t1, rb_t2;
  Vec3 ia_n, ia_t1, ia_t2, ib_n, ib_t1, ib_t2;
  double adjusted_separation = 0.0;  // m: s_0 - n . (r_B - r_A)
  double mass_n = 0.0, mass_t1 = 0.0, mass_t2 = 0.0;  // kg
  double k_t12 = 0.0;          // 1/kg, K's coupling of t1 and t2 (slip_friction_step.h)
  double friction = 0.0, restitution = 0.0;
  double impact_speed = 0.0;   // m/s, relative normal velocity at impact (< 0 approaching)
  double lambda_n = 0.0, lambda_t1 = 0.0, lambda_t2 = 0.0;  // N s per sub-step, accumulated
  double max_push = 0.0;       // N s, largest normal increment of the step
  double total_n = 0.0;        // N s over the step
  double total_t1 = 0.0, total_t2 = 0.0;  // N s over the step along t1, t2
  Softness soft;               // of this point's spring (SoftSprings)

  // relative velocity of B against A at the anchors along n, t1, t2
  double VelocityAlong(const Vec3& d, const Vec3& ja, const Vec3& jb, const SoftBody& A, const SoftBody& B) const {
    return d.dot(B.v - A.v) + jb.dot(B.w) - ja.dot(A.w);
  }
  // the same along n, from the anchors (the normal row's Jacobians need
  // not be set; the same value as from them)
  double NormalVelocity(const SoftBody& A, const SoftBody& B) const {
    return VelocityAlong(n, ra.cross(n), rb.cross(n), A, B);
  }
  // +impulse * d on B at r_B, -impulse * d on A at r_A (a static or
  // kinematic body is never written: many threads may hold it at once,
  // block_colours.h)
  static void Push(double impulse, const Vec3& d, const Vec3& ia, const Vec3& ib, SoftBody& A, SoftBody& B) {
    PushImpulse(impulse, d, ia, ib, A, B);
  }
};

// A step's springs for sub-steps of h: `hertz` between two movable bodies,
// twice it against a static or kinematic one, which carries no share of
// the motion (Box2D v3's static softness).
struct SoftSprings {
  Softness movable, fixed;
  SoftSprings(double hertz, double damping_ratio, double h)
      : movable(MakeSoftness(hertz, damping_ratio, h)), fixed(MakeSoftness(2.0 * hertz, damping_ratio, h)) {}
};

// The points of `contacts` at the bodies' state at the step's start, their
// friction rows acting at `friction_points` (patch_torsion.h; null: at the
// contact points), each with its spring of `springs` (set as the point is
// made: a pass of its own over the points fetched two cache lines of each
// again, BENCHMARKS.md "Scaling: 1,000 to 10,000 bodies"). On the
// world's threads (each point is its own). Without
// `rows` the rows' Jacobians, responses and effective masses are left
// unset (the masses 0): the float path computes them in float over its
// lanes (soft_wide_kernels.h), and PrepareSoftRows fills them in where the
// double state needs them after all (the step turns to the double path,
// restitution).
void PrepareSoftPoints(const ContactSet& contacts, const World& world, const std::vector<SoftBody>& bodies,
                       const std::vector<Vec3>* friction_points, const SoftSprings& springs, ParallelRunner& runner,
                       std::vector<SoftPoint>* points, bool rows = true);
// One of them, into *out (every field written; without rows their
// Jacobians and responses are left as they were); friction_point null: at
// c.point; `same_frame`, when given, a point of the same pair with the same
// normal, whose tangents and materials *out takes.
void PrepareSoftPoint(const Contact& c, const World& world, const std::vector<SoftBody>& bodies,
                      const Vec3* friction_point, const SoftSprings& springs, bool rows,
                      const SoftPoint* same_frame, SoftPoint* out);
// Where point k's friction acts, from A's and B's centres of mass at the
// step's start: its anchors, or friction_points[k] (patch_torsion.h).
void SoftFrictionArms(const SoftPoint& p, int k, const std::vector<Vec3>* friction_points,
                      const std::vector<SoftBody>& bodies, Vec3* fa, Vec3* fb);
// The rows of points prepared without them, as PrepareSoftPoints computes
// them from `bodies`' inverse masses and inertias at the step's start: the
// normal row's, and with `friction_rows` the friction rows'.
void PrepareSoftRows(const std::vector<SoftBody>& bodies, const std::vector<Vec3>* friction_points,
                     ParallelRunner& runner, std::vector<SoftPoint>* points, bool friction_rows = true);

// The points each dynamic body takes part in, in point order, for the warm
// start body by body: a body sums its points' impulses in the order a sweep
// over the points would, so the result is that sweep's bit for bit, on any
// number of threads. (The order of these sums matters: through round-off it
// decided whether a plank on two 1,000-times lighter boxes held.)
struct SoftPointsOfBodies {
  std::vector<int> start;    // body i's entries are [start[i], start[i + 1])
  std::vector<int> entries;  // 2 k for point k's body A, 2 k + 1 for its B

  // `point_of_contact` (soft_point_order.h): where contact k's point is,
  // the sums still taken in contact order; null: point k is contact k's
  void Build(const std::vector<SoftPoint>& points, const std::vector<SoftBody>& bodies,
             const std::vector<int>* point_of_contact = nullptr);
};

// Applies the accumulated impulses of body i's points to it (warm start of
// a sub-step).
void WarmStartSoftBody(int i, const SoftPointsOfBodies& list, const std::vector<SoftPoint>& points,
                       std::vector<SoftBody>& bodies);

struct SoftPass {
  double inv_h = 0.0;               // 1 / sub-step
  bool use_bias = true;             // false: the relax pass
  // relax: a separated point with lambda_n > 0 is rigid at v_n >= 0 (keeps its gap)
  bool hold_pushing_gaps = false;
  double max_push_velocity = 3.0;   // m/s
};

// What a normal row aims at this pass: J v >= -bias, with the softness's
// mass and impulse scales (1 and 0 for a rigid row).
struct SoftRowTarget {
  double bias = 0.0;  // m/s
  double mass_scale = 1.0;
  double impulse_scale = 0.0;
};
// at separation s (m)
SoftRowTarget SoftNormalTarget(const SoftPass& pass, const SoftPoint& p, double s);
// The point's separation now, from its anchors and the bodies' motion.
double SoftSeparation(const SoftPoint& p, const SoftBody& A, const SoftBody& B);

// One point's rows: the normal on its own, the friction disk; and setting
// the accumulated normal impulse to `total` (>= 0).
void SolveSoftNormal(const SoftPass& pass, SoftPoint& p, SoftBody& A, SoftBody& B);
void SolveSoftFriction(SoftPoint& p, SoftBody& A, SoftBody& B);
void ApplySoftNormal(double total, SoftPoint& p, SoftBody& A, SoftBody& B);

// Adds the point's accumulated impulses to its step totals (end of a sub-step).
void AccumulateSoftTotals(SoftPoint& p);

}  // namespace contactsim
