// The float path's contact constraints, structure of arrays (Box2D v3 and
// Box3D's b2ContactConstraintSIMD): a bundle holds `width` manifolds of one
// colour (block_colours.h), one a lane, so no two lanes share a movable
// body and a pass updates all of them at once. Each field of a bundle is
// `width` consecutive floats, aligned for a SIMD load; a manifold's up to
// kMaxNormalBlock points are its lane's slots.
//
// Only plain types here: the kernels (soft_wide_kernels.h) are compiled
// once per instruction set.
#pragma once

namespace contactsim {
namespace wide {

constexpr int kSlots = 4;  // kMaxNormalBlock (normal_block.h; checked where the bundles are packed)
constexpr int kAlign = 64;  // bytes, a cache line and the widest vector

// Per lane: the pair's normal and tangents, inverse masses, friction
// coefficient and spring (shared by its points: the materials' and the
// bodies', SoftSprings), its points, whether the normal rows take
// the block solve and its K^-1 (row-major).
enum LaneField : int {
  kN = 0,
  kT1 = 3,
  kT2 = 6,
  kInvMassA = 9,
  kInvMassB = 10,
  kCount = 11,  // the manifold's points (0 in a padding lane)
  kFriction = 12,
  kBiasRate = 13,
  kMassScale = 14,
  kImpulseScale = 15,
  kBlock = 16,  // 1 or 0
  kInvK = 17,
  kLaneFields = kInvK + 16,
};

// Per slot (point): the rows' anchors, Jacobians and responses
// (SoftPoint), effective masses, accumulated impulses and totals.
// The bundles are packed with the anchors, where friction acts (kFa, kFb:
// the patch's point, patch_torsion.h; not packed where it acts at the
// anchors, WideView::friction_at_anchors) and the warm start; the prepare kernel (soft_wide_kernels.h) computes the rest
// (Jacobians, responses, effective masses, K^-1) over the lanes.
enum SlotField : int {
  kRa = 0,
  kRb = 3,
  kRaN = 6,
  kRbN = 9,
  kIaN = 12,
  kIbN = 15,
  kRaT1 = 18,
  kRaT2 = 21,
  kRbT1 = 24,
  kRbT2 = 27,
  kIaT1 = 30,
  kIaT2 = 33,
  kIbT1 = 36,
  kIbT2 = 39,
  kSeparation = 42,  // m, s_0: the separation at the step's start
  kMassN,
  kMassT1,
  kMassT2,
  kKT12,
  kLambdaN,
  kLambdaT1,
  kLambdaT2,
  kMaxPush,
  kTotalN,
  kTotalT1,
  kTotalT2,
  kFa,
  kFb = kFa + 3,
  kSlotFields = kFb + 3,
};

// fields of a bundle whose lanes hold at most `slots` points
constexpr int BundleFields(int slots) { return kLaneFields + slots * kSlotFields; }
// field index of slot s's field f
constexpr int SlotAt(int s, int f) { return kLaneFields + s * kSlotFields + f; }

// A body as the contact passes see it (WideBodies, soft_wide_bodies.h).
struct WideBody {
  float v[3] = {0, 0, 0};   // m/s
  float w[3] = {0, 0, 0};   // rad/s, world
  float dp[3] = {0, 0, 0};  // m, x - x0
  // R(q) R(q0)^T - I, column-major: the turn since the step's start kept
  // apart from the identity, so that a resting body's turn keeps float's
  // digits (soft_wide_kernels_impl.h, NormalTargets)
  float turn[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};

  // the 18 floats in the order above, for the kernels' gathers
  const float* Floats() const { return v; }
  float* Floats() { return v; }
};
constexpr int kWideBodyFloats = 18;
static_assert(sizeof(WideBody) == kWideBodyFloats * sizeof(float), "WideBody's floats lie end to end");

// What a kernel call sees of the bundles and the bodies.
struct WideView {
  // body i's world inverse inertia at the step's start, column-major:
  // inv_inertia + i * inertia_stride (read by the prepare kernel only)
  const float* inv_inertia = nullptr;
  int inertia_stride = 0;
  float* data = nullptr;           // bundle b's field f: data + offsets[b] + f * width
  const int* offsets = nullptr;    // per bundle, floats (a bundle holds BundleFields(slots[b]) fields)
  const int* body_a = nullptr;     // per bundle lane: WideBody index (padding: the resting dummy)
  const int* body_b = nullptr;
  const unsigned char* write_a = nullptr;  // per bundle lane: 1 when the body is dynamic
  const unsigned char* write_b = nullptr;
  const unsigned char* slots = nullptr;    // per bundle: most points of its lanes
  WideBody* bodies = nullptr;
  // friction acts at the anchors: kFa and kFb are not packed (patch
  // torsion off, patch_torsion.h)
  bool friction_at_anchors = true;
  int width = 0;
};

// One pass (SoftPass, in float).
struct WidePass {
  float inv_h = 0.0f;
  bool use_bias = true;
  // relax: a separated point with lambda_n > 0 is rigid at v_n >= 0 (keeps its gap)
  bool hold_pushing_gaps = false;
  float max_push_velocity = 3.0f;
};

}  // namespace wide
}  // namespace contactsim
