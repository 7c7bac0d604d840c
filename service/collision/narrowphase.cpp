// Narrowphase dispatch: a table of pair functions indexed by the two shape
// types (MuJoCo, engine_collision_driver.c, mjCOLLISIONFUNC). Only one
// triangle is filled; a pair (B, A) found only as (A, B) is collided with the
// bodies swapped and its normals flipped, so every pair function is written
// once and swapping the bodies gives the same points.
#include "service/collision/narrowphase.h"

#include <algorithm>
#include <array>

#include "service/collision/collide_pairs.h"
#include "service/collision/compound_children.h"
#include "service/collision/feature_id.h"
#include "service/collision/polyhedron_sat.h"
#include "service/collision/region_probe.h"
#include "service/collision/separating_axis_cache.h"

namespace contactsim {
namespace {

constexpr int kShapeTypes = static_cast<int>(ShapeType::kCount);

// Pairs per parallel task, at least: a pair costs from ~0.1 us (a cache hit)
// to a few us (a clipped manifold) and a oneTBB task about 1 us, so fewer
// would spend more on scheduling than on pairs.
constexpr int kPairGrain = 16;

// rows: shape of body a; columns: shape of body b
const std::array<std::array<PairCollider, kShapeTypes>, kShapeTypes> kCollisionTable = {{
    //  sphere               box                       capsule                 convex                    plane  compound
    //  mesh            heightfield
    {{CollideSphereSphere, CollideSphereBox, CollideSphereCapsule, CollideSphereConvex, CollideSpherePlane, nullptr,
      CollideSurface, CollideSurface}},
    {{nullptr, CollidePolyhedra, nullptr, CollidePolyhedra, CollidePolyhedronPlane, nullptr, CollideSurface,
      CollideSurface}},
    {{nullptr, CollideCapsulePolyhedron, CollideCapsuleCapsule, CollideCapsulePolyhedron, CollideCapsulePlane, nullptr,
      CollideSurface, CollideSurface}},
    {{nullptr, nullptr, nullptr, CollidePolyhedra, CollidePolyhedronPlane, nullptr, CollideSurface, CollideSurface}},
    {{nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}},  // plane: static, touches no static
    {{nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}},  // compound: by its children
    {{nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}},  // mesh: static (row of the other)
    {{nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}},  // heightfield: static
}};

// Canonical order of two bodies of the same shape type, so that (a, b) and
// (b, a) run the same computation: by id, then by pose (callers without a
// world may leave every id at 0).
bool Precedes(const RigidBody& a, const RigidBody& b) {
  if (a.id != b.id) return a.id < b.id;
  for (int k = 0; k < 3; ++k) {
    if (a.x[k] != b.x[k]) return a.x[k] < b.x[k];
  }
  for (int k = 0; k < 4; ++k) {
    if (a.q.coeffs()[k] != b.q.coeffs()[k]) return a.q.coeffs()[k] < b.q.coeffs()[k];
  }
  return true;
}

bool PoseIsFinite(const RigidBody& body) { return IsFinite(body.x) && IsFinite(body.q); }

int DispatchCompound(const RigidBody& a, int ia, const RigidBody& b, int ib, const CollideContext& ctx,
                     ContactSet* out);

int Dispatch(const RigidBody& a, int ia, const RigidBody& b, int ib, const CollideContext& ctx,
             ContactSet* out) {
  // non-finite poses have no meaningful contacts; the state checks report them
  if (!PoseIsFinite(a) || !PoseIsFinite(b)) return 0;
  const int ta = static_cast<int>(a.shape.type);
  const int tb = static_cast<int>(b.shape.type);
  constexpr int kCompound = static_cast<int>(ShapeType::kCompound);
  if (ta == kCompound || tb == kCompound) return DispatchCompound(a, ia, b, ib, ctx, out);
  if (ta < 0 || ta >= kShapeTypes || tb < 0 || tb >= kShapeTypes) return 0;

  PairCollider fn = kCollisionTable[ta][tb];
  bool swapped = false;
  if (fn == nullptr || (ta == tb && !Precedes(a, b))) {
    fn = kCollisionTable[tb][ta];
    swapped = true;
  }
  if (fn == nullptr) return 0;

  const size_t first = out->size();
  if (swapped) {
    fn(b, a, ctx, out);
  } else {
    fn(a, b, ctx, out);
  }
  for (size_t k = first; k < out->size(); ++k) {
    Contact& c = (*out)[k];
    c.a = ia;
    c.b = ib;
    c.id_a = a.id;
    c.id_b = b.id;
    if (swapped) c.normal = -c.normal;
  }
  return static_cast<int>(out->size() - first);
}

// A compound collides child by child with the other body's pieces (its
// children, or itself), each child pair through the table. The pair is
// taken in one order (by id, as Precedes), so that (a, b) and (b, a) give
// the same points; each point's feature id also hashes the two children's
// indices, so warm starts and manifolds stay per child pair. The
// separating-axis cache holds one axis per body pair, not per child pair:
// children run without it, unless each side has one piece (a model's link
// of one collision mesh), whose child pair is the body pair.
int DispatchCompound(const RigidBody& a, int ia, const RigidBody& b, int ib, const CollideContext& ctx,
                     ContactSet* out) {
  const bool swapped = !Precedes(a, b);
  const RigidBody& first = swapped ? b : a;
  const RigidBody& second = swapped ? a : b;
  CollideContext child_ctx = ctx;
  const int n1 = PieceCount(first), n2 = PieceCount(second);
  if (n1 != 1 || n2 != 1) {
    child_ctx.cache = nullptr;
    child_ctx.cache_update = nullptr;
  }
  const size_t begin = out->size();
  for (int k1 = 0; k1 < n1; ++k1) {
    const RigidBody p1 = PieceBody(first, k1);
    for (int k2 = 0; k2 < n2; ++k2) {
      const size_t before = out->size();
      Dispatch(p1, 0, PieceBody(second, k2), 0, child_ctx, out);
      for (size_t k = before; k < out->size(); ++k) {
        Contact& c = (*out)[k];
        c.feature_id = FeatureId({c.feature_id, static_cast<uint32_t>(k1), static_cast<uint32_t>(k2)});
      }
    }
  }
  for (size_t k = begin; k < out->size(); ++k) {
    Contact& c = (*out)[k];
    c.a = ia;
    c.b = ib;
    c.id_a = a.id;
    c.id_b = b.id;
    if (swapped) c.normal = -c.normal;
  }
  return static_cast<int>(out->size() - begin);
}

}  // namespace

void AppendContact(const Vec3& surface_a, const Vec3& normal_ab, double depth, uint32_t feature_id,
                   ContactSet* out) {
  Contact c;
  // B's surface point is surface_a - depth * normal; the contact point is midway
  c.point = surface_a - 0.5 * depth * normal_ab;
  c.normal = normal_ab;
  c.depth = depth;
  c.feature_id = feature_id;
  out->push_back(c);
}

void PlaneInWorld(const RigidBody& plane, Vec3* normal_W, double* offset_W) {
  // n_B . p_B = o with p_W = R p_B + x gives (R n_B) . p_W = o + (R n_B) . x
  *normal_W = plane.q * plane.shape.plane_normal.normalized();
  *offset_W = plane.shape.plane_offset + normal_W->dot(plane.x);
}

void CapsuleSegment(const RigidBody& capsule, Vec3* p0_W, Vec3* p1_W) {
  const Vec3 half_axis = capsule.q * Vec3(0.0, 0.0, capsule.shape.half_length);
  *p0_W = capsule.x - half_axis;
  *p1_W = capsule.x + half_axis;
}

int Collide(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin, ContactSet* out) {
  CollideContext ctx;
  ctx.margin = margin;
  return Dispatch(a, ia, b, ib, ctx, out);
}

double PairSignedDistance(const RigidBody& a, const RigidBody& b, double margin, Vec3* normal) {
  PosedPolyhedron pa, pb;
  if (PoseIsFinite(a) && PoseIsFinite(b) && PosePolyhedron(a, &pa) && PosePolyhedron(b, &pb)) {
    const SatResult sat = FindSeparatingAxis(pa, pb, margin);
    if (normal != nullptr && sat.max_separation < margin) *normal = sat.max_normal;
    return std::min(margin, sat.max_separation);
  }
  ContactSet contacts;
  Collide(a, 0, b, 1, margin, &contacts);
  double distance = margin;
  for (const Contact& c : contacts) {
    if (-c.depth >= distance) continue;
    distance = -c.depth;
    if (normal != nullptr) *normal = c.normal;
  }
  return distance;
}

int Narrowphase::Collide(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin,
                         ContactSet* out) {
  AxisCacheUpdate update;
  CollideContext ctx;
  ctx.margin = margin;
  ctx.cache = &cache_;
  ctx.cache_update = &update;
  ctx.scratch = &scratch_;
  const int added = Dispatch(a, ia, b, ib, ctx, out);
  cache_.Apply(update);
  return added;
}

int Narrowphase::CollideReadOnly(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin,
                                 ContactSet* out) const {
  AxisCacheUpdate discarded;
  CollideContext ctx;
  ctx.margin = margin;
  ctx.cache = &cache_;
  ctx.cache_update = &discarded;
  return Dispatch(a, ia, b, ib, ctx, out);
}

void Narrowphase::CollidePairs(const std::vector<RigidBody>& bodies, const std::vector<BodyPair>& pairs,
                               double margin, ParallelRunner& runner, ContactSet* out) {
  const int n = static_cast<int>(pairs.size());
  updates_.assign(pairs.size(), AxisCacheUpdate());
  if (manifold_reuse_) {
    // only the outcome's fields: a manifold is written when one is made
    manifold_updates_.resize(pairs.size());
    for (ManifoldUpdate& u : manifold_updates_) {
      u.kind = ManifoldUpdate::Kind::kNone;
      u.reuses = u.remakes = 0;
    }
    manifolds_.Locate(bodies, pairs, &kept_);
  }
  // every pair reads the caches as they were before the detection and
  // writes its change aside; the caches are rebuilt from the changes in
  // pair order
  auto collide = [&](int i, PolyhedronScratch* scratch, ContactSet* contacts) {
    CollidePair(bodies, pairs[i], i, margin, scratch, contacts);
  };
  if (runner.threads() == 1 || n <= kPairGrain) {  // the serial path
    {
      const ParallelRegionProbe probe(n > kPairGrain);  // the pairs' loop runs on the threads when there are more
      for (int i = 0; i < n; ++i) collide(i, &scratch_, out);
    }
    RebuildCaches();
    return;
  }
  // slots and scratch only grow, so a warmed-up step allocates nothing
  if (slots_.size() < pairs.size()) slots_.resize(pairs.size());
  if (worker_scratch_.size() < static_cast<size_t>(runner.threads())) worker_scratch_.resize(runner.threads());
  runner.For(n, kPairGrain, [&](int begin, int end, int worker) {
    for (int i = begin; i < end; ++i) {
      slots_[i].clear();
      collide(i, &worker_scratch_[worker], &slots_[i]);
    }
  });
  // pair order, as the serial loop appends
  for (int i = 0; i < n; ++i) out->insert(out->end(), slots_[i].begin(), slots_[i].end());
  RebuildCaches();
}

void Narrowphase::CollidePair(const std::vector<RigidBody>& bodies, const BodyPair& p, int i, double margin,
                              PolyhedronScratch* scratch, ContactSet* out) {
  const RigidBody& a = bodies[p.first];
  const RigidBody& b = bodies[p.second];
  const bool keeps = manifold_reuse_ && KeepsManifold(a, b);
  if (keeps && manifolds_.ReuseAt(kept_[i], a, p.first, b, p.second, margin, &manifold_updates_[i], out)) return;
  CollideContext ctx;
  ctx.margin = margin;
  ctx.cache = &cache_;
  ctx.cache_update = &updates_[i];
  ctx.scratch = scratch;
  const size_t first = out->size();
  Dispatch(a, p.first, b, p.second, ctx, out);
  if (keeps) {
    ManifoldCache::Record(a, b, out->data() + first, static_cast<int>(out->size() - first), &manifold_updates_[i]);
  }
}

void Narrowphase::RebuildCaches() {
  cache_.Rebuild(updates_);
  if (manifold_reuse_) manifolds_.Rebuild(manifold_updates_);
}

}  // namespace contactsim
