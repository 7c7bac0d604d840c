// Capsule pairs. A capsule is the segment between its cap centres p0, p1
// with radius r, so each pair reduces to sphere contacts placed at points of
// the segment (see collide_sphere.cpp for the sphere formulas).
#include <algorithm>
#include <cmath>

#include "service/collision/closest_points.h"
#include "service/collision/collide_pairs.h"

namespace contactsim {
namespace {

// Segments with sin(angle) below this are parallel: lying side by side they
// touch along an interval, which gets a contact at each end (one point would
// let them roll about it). 1e-3 rad is well below what the eye calls tilted.
constexpr double kParallelSin = 1e-3;
// Overlap intervals shorter than this (m) are a single point.
constexpr double kDistinctLength = 1e-6;

}  // namespace

// capsule-capsule: the closest points of the two axes (Ericson 5.1.9) are the
// centres of two touching spheres; parallel overlapping axes give a contact
// at each end of their overlap.
void CollideCapsuleCapsule(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                           ContactSet* out) {
  Vec3 a0, a1, b0, b1;
  CapsuleSegment(a, &a0, &a1);
  CapsuleSegment(b, &b0, &b1);
  const double ra = a.shape.radius;
  const double rb = b.shape.radius;
  const Vec3 da = a1 - a0;
  const Vec3 db = b1 - b0;
  const double la_sq = da.squaredNorm();
  const double lb_sq = db.squaredNorm();
  if (la_sq > 0.0 && lb_sq > 0.0 &&
      da.cross(db).squaredNorm() < kParallelSin * kParallelSin * la_sq * lb_sq) {
    // overlap of B's axis projected on A's, in A's parameter
    const double s0 = (b0 - a0).dot(da) / la_sq;
    const double s1 = (b1 - a0).dot(da) / la_sq;
    const double lo = std::max(0.0, std::min(s0, s1));
    const double hi = std::min(1.0, std::max(s0, s1));
    if ((hi - lo) * std::sqrt(la_sq) > kDistinctLength) {
      const double ends[2] = {lo, hi};
      for (int k = 0; k < 2; ++k) {
        const Vec3 pa = a0 + ends[k] * da;
        AppendBallContact(pa, ra, ClosestPointOnSegment(pa, b0, b1), rb, 1 + k, ctx.margin, out);
      }
      return;
    }
  }
  const SegmentClosestPoints cp = ClosestPointsOfSegments(a0, a1, b0, b1);
  AppendBallContact(cp.c1, ra, cp.c2, rb, 0, ctx.margin, out);
}

// capsule-plane: each cap sphere against the plane, d = n.p - offset.
void CollideCapsulePlane(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                         ContactSet* out) {
  Vec3 ends[2];
  CapsuleSegment(a, &ends[0], &ends[1]);
  Vec3 n;
  double offset;
  PlaneInWorld(b, &n, &offset);
  for (int k = 0; k < 2; ++k) {
    AppendSphereContact(ends[k], a.shape.radius, n.dot(ends[k]) - offset, n, k, ctx.margin, out);
  }
}

}  // namespace contactsim
