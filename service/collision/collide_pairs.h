// The pair functions of the narrowphase table (narrowphase.cpp), one file per
// family as MuJoCo's engine_collision_*.c:
//   collide_sphere.cpp      sphere-sphere, sphere-plane, sphere-box,
//                           sphere-capsule, sphere-convex
//   collide_capsule.cpp     capsule-capsule, capsule-plane
//   collide_capsule_polyhedron.cpp  capsule-box, capsule-convex (segment SAT)
//   collide_polyhedron.cpp  box/convex-plane, box/convex-box/convex (SAT)
//   collide_surface.cpp     any of these against a triangle mesh or heightfield
//
// Every function collides body `a` (the row shape of the table) with body `b`
// and appends contacts whose depth > -margin, filling only point, normal
// (unit, world, from a to b), depth and feature_id; the dispatcher fills the
// body indices and ids and flips the normal when it swapped the bodies.
#pragma once

#include <cstdint>

#include "service/collision/contact.h"
#include "service/collision/minkowski_edge_pairs.h"
#include "service/collision/polyhedron_manifold.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

class SeparatingAxisCache;
struct AxisCacheUpdate;

// Posed polyhedra and clip polygons of the polyhedron pairs, reused between
// pairs (and steps) so that a step allocates nothing once warmed up.
struct PolyhedronScratch {
  PosedPolyhedron a, b;
  ClipBuffers clip;
  ContactSet triangle, surface;  // a mesh pair's contacts per triangle and in all
  EdgePairScratch edge_pairs;
};

// The cache is only read during a pair; its change goes to `cache_update`
// (both or neither given), so that pairs may run on several threads
// (separating_axis_cache.h). The scratch belongs to one thread.
struct CollideContext {
  double margin = 0.0;                         // m: report pairs with separation < margin
  const SeparatingAxisCache* cache = nullptr;  // optional, used by the polyhedron pairs
  AxisCacheUpdate* cache_update = nullptr;     // this pair's change to `cache`
  PolyhedronScratch* scratch = nullptr;        // optional, used by the polyhedron pairs
};

using PairCollider = void (*)(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                              ContactSet* out);

// Appends one contact between surfaces A and B given the unit normal from A to
// B, the depth, and a point on A's surface: the contact point is moved half
// the depth towards B's surface so that it lies midway between the two.
void AppendContact(const Vec3& surface_a, const Vec3& normal_ab, double depth, uint32_t feature_id,
                   ContactSet* out);

// Sphere A (centre c, radius r) against a surface at signed distance d from c
// whose outward unit normal at its nearest point is m: depth r - d, normal -m.
void AppendSphereContact(const Vec3& c, double r, double d, const Vec3& m, uint32_t feature_id,
                         double margin, ContactSet* out);
// Sphere A (ca, ra) against sphere B (cb, rb).
void AppendBallContact(const Vec3& ca, double ra, const Vec3& cb, double rb, uint32_t feature_id,
                       double margin, ContactSet* out);

void CollideSphereSphere(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
void CollideSpherePlane(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
void CollideSphereBox(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
void CollideSphereCapsule(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
void CollideSphereConvex(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);

void CollideCapsuleCapsule(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
void CollideCapsulePlane(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
// capsule-box and capsule-convex
void CollideCapsulePolyhedron(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);

// Segment [p0, p1] grown by r (a capsule) against a posed polyhedron; `box`,
// when given, is the box body `poly` was posed from (its closed-form distance).
void CollideSegmentPolyhedron(const Vec3& p0, const Vec3& p1, double r, const PosedPolyhedron& poly,
                              const RigidBody* box, double margin, ContactSet* out);
// Contacts at the ends of segment [p0, p1] (radius r) clipped to the prism
// over face f of `poly`, each at its own height above the face; returns the
// deepest depth appended (or -inf).
double AppendCapsuleFaceContacts(const Vec3& p0, const Vec3& p1, double r, const PosedPolyhedron& poly, int f,
                                 double margin, ContactSet* out);

// sphere, box, capsule or convex (a) - mesh or heightfield (b): triangle by
// triangle with the surface's edge rule (collide_surface.cpp)
void CollideSurface(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);

// box-plane and convex-plane
void CollidePolyhedronPlane(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);
// box-box, box-convex and convex-convex
void CollidePolyhedra(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out);

// World-frame plane of a plane body: n . p = offset, solid side n . p <= offset.
void PlaneInWorld(const RigidBody& plane, Vec3* normal_W, double* offset_W);

// Capsule axis end points (cap centres) in the world frame.
void CapsuleSegment(const RigidBody& capsule, Vec3* p0_W, Vec3* p1_W);

}  // namespace contactsim
