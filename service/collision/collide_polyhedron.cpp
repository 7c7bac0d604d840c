// Polyhedron pairs: box and convex hull against a plane (closed form over the
// vertices) and against each other (separating-axis test + face clipping).
#include <cstdint>
#include <optional>

#include "service/collision/box_box_manifold.h"
#include "service/collision/box_box_sat.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/feature_id.h"
#include "service/collision/manifold_reduction.h"
#include "service/collision/polyhedron_manifold.h"
#include "service/collision/polyhedron_sat.h"
#include "service/collision/separating_axis_cache.h"

namespace contactsim {

// box/convex (a) - plane (b): every vertex v with signed distance
// s = n.v - offset < margin is a contact of depth -s, normal -n (from the
// body to the plane, whose solid side is below), point midway between v and
// its projection on the plane. Feature id = vertex index. A face resting on
// the plane gives its corners; more than four are reduced to four.
void CollidePolyhedronPlane(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                            ContactSet* out) {
  PosedPolyhedron local;
  PosedPolyhedron& poly = ctx.scratch != nullptr ? ctx.scratch->a : local;
  if (!PosePolyhedron(a, &poly)) return;
  Vec3 n;
  double offset;
  PlaneInWorld(b, &n, &offset);
  const size_t first = out->size();
  for (size_t i = 0; i < poly.vertices.size(); ++i) {
    const double s = n.dot(poly.vertices[i]) - offset;
    if (-s <= -ctx.margin) continue;
    AppendContact(poly.vertices[i], -n, -s, static_cast<uint32_t>(i), out);
  }
  ReduceManifold(first, out);
}

// box (a) - box (b): the closed-form separating-axis test for a contact (box_box_sat.h)
// and, for a touching pair, the manifold from the same poses
// (box_box_manifold.h), so that nothing is posed; `cached` says whether
// the pair's axis goes to the cache.
void CollideBoxes(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, bool cached, ContactSet* out) {
  const BoxPose pa(a), pb(b);
  const SatResult sat = FindBoxBoxContactAxis(pa, pb, ctx.margin);
  if (sat.separation > ctx.margin) {
    if (cached) ctx.cache_update->Store(a.id, b.id, sat.axis);
    return;
  }
  if (cached) ctx.cache_update->Erase(a.id, b.id);
  BoxBoxManifold(pa, pb, sat, ctx.margin, out);
}

// box/convex (a) - box/convex (b): separating-axis test, with the axis that
// separated the pair last call tried first when a cache is given (Baraff);
// two boxes take CollideBoxes.
void CollidePolyhedra(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                      ContactSet* out) {
  // equal ids (callers without a world) cannot be told apart in the cache
  const SeparatingAxisCache* cache = a.id != b.id && ctx.cache_update != nullptr ? ctx.cache : nullptr;
  AxisCacheUpdate* update = ctx.cache_update;
  // a hit is decided on the bodies' own frames, before anything is posed
  if (cache != nullptr) {
    const SeparatingAxis* kept = cache->StillSeparatingAxis(a, b, ctx.margin);
    ++(kept != nullptr ? update->hits : update->misses);
    if (kept != nullptr) {
      update->Store(a.id, b.id, *kept);  // so that the rebuilt cache keeps it
      return;
    }
  }
  if (a.shape.type == ShapeType::kBox && b.shape.type == ShapeType::kBox) {
    CollideBoxes(a, b, ctx, cache != nullptr, out);
    return;
  }
  // a caller without scratch gets one for this pair; the others construct none
  std::optional<PolyhedronScratch> local;
  PolyhedronScratch& scratch = ctx.scratch != nullptr ? *ctx.scratch : local.emplace();
  PosedPolyhedron& pa = scratch.a;
  PosedPolyhedron& pb = scratch.b;
  if (!PosePolyhedron(a, &pa) || !PosePolyhedron(b, &pb)) return;
  const SatResult sat = FindSeparatingAxis(pa, pb, ctx.margin, &scratch.edge_pairs);
  if (sat.separation > ctx.margin) {
    if (cache != nullptr) update->Store(a.id, b.id, sat.axis);
    return;
  }
  if (cache != nullptr) update->Erase(a.id, b.id);
  PolyhedronManifold(pa, pb, sat, ctx.margin, out, &scratch.clip);
}

}  // namespace contactsim
