// Sphere pairs, all closed forms: a sphere is its centre c with radius r, so
// each pair reduces to the signed distance d from c to the other shape (grown
// by its own radius for spheres and capsules) and the outward normal m of the
// other shape at its nearest point. Then, with A the sphere,
//   depth = r - d,  normal (A to B) = -m,
//   sphere surface point c - r m, contact point c - (r + d)/2 m (midway).
// d is continuous in the poses, so the depth is too (speculative contacts).
#include "service/collision/collide_pairs.h"
#include "service/collision/closest_points.h"
#include "service/collision/polyhedron_distance.h"

namespace contactsim {
namespace {

// Centres closer than this (m) have no defined normal between them; +z is used.
constexpr double kCoincident = 1e-12;

}  // namespace

void AppendSphereContact(const Vec3& c, double r, double d, const Vec3& m, uint32_t feature_id,
                         double margin, ContactSet* out) {
  const double depth = r - d;
  if (depth <= -margin) return;
  AppendContact(c - r * m, -m, depth, feature_id, out);
}

void AppendBallContact(const Vec3& ca, double ra, const Vec3& cb, double rb, uint32_t feature_id,
                       double margin, ContactSet* out) {
  const Vec3 delta = ca - cb;
  const double dist = delta.norm();
  const Vec3 m = dist > kCoincident ? Vec3(delta / dist) : Vec3(-Vec3::UnitZ());
  AppendSphereContact(ca, ra, dist - rb, m, feature_id, margin, out);
}

// sphere-sphere: d = |ca - cb| - rb, m = (ca - cb)/|ca - cb|.
void CollideSphereSphere(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                         ContactSet* out) {
  AppendBallContact(a.x, a.shape.radius, b.x, b.shape.radius, 0, ctx.margin, out);
}

// sphere-plane: d = n.c - offset, m = n (the plane's outward normal).
void CollideSpherePlane(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                        ContactSet* out) {
  Vec3 n;
  double offset;
  PlaneInWorld(b, &n, &offset);
  AppendSphereContact(a.x, a.shape.radius, n.dot(a.x) - offset, n, 0, ctx.margin, out);
}

// sphere-box: d and m from the box's closed-form signed distance (clamp the
// centre to the box outside; least face clearance inside).
void CollideSphereBox(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                      ContactSet* out) {
  const SurfaceQuery s = BoxSignedDistance(b, a.x);
  AppendSphereContact(a.x, a.shape.radius, s.distance, s.normal, 0, ctx.margin, out);
}

// sphere-capsule: sphere-sphere with the nearest point of the capsule's axis.
void CollideSphereCapsule(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                          ContactSet* out) {
  Vec3 p0, p1;
  CapsuleSegment(b, &p0, &p1);
  const Vec3 nearest = ClosestPointOnSegment(a.x, p0, p1);
  AppendBallContact(a.x, a.shape.radius, nearest, b.shape.radius, 0, ctx.margin, out);
}

// sphere-convex: d and m from the hull's signed distance.
void CollideSphereConvex(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                         ContactSet* out) {
  PosedPolyhedron poly;
  if (!PosePolyhedron(b, &poly)) return;
  const SurfaceQuery s = PolyhedronSignedDistance(poly, a.x);
  AppendSphereContact(a.x, a.shape.radius, s.distance, s.normal, 0, ctx.margin, out);
}

}  // namespace contactsim
