// Capsule pairs. A capsule is the segment between its cap centres p0, p1
// with radius r, so each pair reduces to sphere contacts placed at points of
// the segment (see collide_sphere.cpp for the sphere formulas).
#include <algorithm>
#include <cmath>
#include <functional>

#include "service/collision/closest_points.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/polyhedron_distance.h"

namespace contactsim {
namespace {

// Segments with sin(angle) below this are parallel: lying side by side they
// touch along an interval, which gets a contact at each end (one point would
// let them roll about it). 1e-3 rad is well below what the eye calls tilted.
constexpr double kParallelSin = 1e-3;
// Overlap intervals shorter than this (m) are a single point.
constexpr double kDistinctLength = 1e-6;
// An interior point of a capsule's axis is added to its end contacts only when
// it is nearer to the other shape than both ends by this much (m); the error
// it allows in the deepest depth is this value.
constexpr double kInteriorTolerance = 1e-7;
// Golden-section iterations on [0, 1]: 0.618^80 ~ 2e-17 of the axis length.
constexpr int kGoldenIterations = 80;

// Minimiser of a convex function on [0, 1] by golden-section search.
double MinimiseConvex(const std::function<double(double)>& f) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 1.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < kGoldenIterations && hi - lo > 1e-15; ++i) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = f(x2);
    }
  }
  return 0.5 * (lo + hi);
}

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

// capsule-box and capsule-convex: the signed distance of the polyhedron along
// the capsule's axis is convex, so golden-section search finds its minimum.
// Contacts: both cap spheres (so that a capsule lying on a face rests on two
// points), and the minimiser when it is nearer than both ends (an axis lying
// across an edge). The deepest contact is then the exact minimum up to
// kInteriorTolerance, so the depth stays continuous.
void CollideCapsulePolyhedron(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                              ContactSet* out) {
  PosedPolyhedron poly;
  const bool is_box = b.shape.type == ShapeType::kBox;
  if (!is_box && !PosePolyhedron(b, &poly)) return;
  const auto query = [&](const Vec3& p) {
    return is_box ? BoxSignedDistance(b, p) : PolyhedronSignedDistance(poly, p);
  };
  Vec3 p0, p1;
  CapsuleSegment(a, &p0, &p1);
  const double r = a.shape.radius;

  const SurfaceQuery q0 = query(p0);
  const SurfaceQuery q1 = query(p1);
  const double t = MinimiseConvex([&](double u) { return query(p0 + u * (p1 - p0)).distance; });
  const Vec3 pt = p0 + t * (p1 - p0);
  const SurfaceQuery qt = query(pt);

  AppendSphereContact(p0, r, q0.distance, q0.normal, 0, ctx.margin, out);
  if (qt.distance < std::min(q0.distance, q1.distance) - kInteriorTolerance) {
    AppendSphereContact(pt, r, qt.distance, qt.normal, 2, ctx.margin, out);
  }
  AppendSphereContact(p1, r, q1.distance, q1.normal, 1, ctx.margin, out);
}

}  // namespace contactsim
