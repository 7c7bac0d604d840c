// Stable penalty friction after Yamane and Nakamura, "Stable penalty-based
// model of frictional contacts", ICRA 2006: a tangential spring-damper from
// an anchor laid down where the contact began, limited by Coulomb's law.
//   f_t = -kt s - ct v_t   (s: stretch, v_t: tangential slip velocity)
// While |f_t| <= mu lambda the anchor holds (static friction: the spring
// carries the load with a displacement of |f_t| / kt, no creep); when the
// trial force leaves the disk, f_t is scaled back onto it and the anchor
// slides so that the spring alone carries it, s = -f_t / kt (dynamic
// friction, |f_t| = mu lambda).
//
// Why a stretch rather than two material anchor points: the stretch s is
// the contact point minus the anchor, advanced by the slip velocity at the
// contact, s += h v_t, so a sphere rolling without slip does not wind the
// spring up (two material points would separate as it rolls and resist the
// rolling). The anchor itself is point - s.
//
// Anchors are kept per contact feature, keyed by (lower body id, higher
// body id, feature id) in a std::map (deterministic order); a contact that
// stops carrying force loses its anchor.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <tuple>

#include "service/collision/contact.h"
#include "service/physics/byte_stream.h"

namespace contactsim {

struct AnchorState {
  Vec3 stretch = Vec3::Zero();  // m, world, tangent: B's contact point minus the anchor
  bool penetrating = false;     // depth > 0 in the step that stored it
  double impact_speed = 0.0;    // m/s, approach speed when the contact began
  // m: > 0 the overlap the pair was placed with, left of it (penalty_row.h);
  // < 0 a placed start's compression (penalty_preload.h)
  double rest_depth = 0.0;
};

class FrictionAnchors {
 public:
  // The state of contact c as seen from c's A and B (stretch of B relative
  // to A); false when c has no anchor yet.
  bool Find(const Contact& c, AnchorState* state) const;
  // Keeps c's state for the next step; contacts not kept are dropped by Commit.
  void Keep(const Contact& c, const AnchorState& state);
  // The rest depth a new point of the pair of bodies a, b starts with, from
  // the points of the pair kept in the last step: their largest if any is
  // >= 0 (a placed overlap), else their mean (a placed start's compression,
  // penalty_preload.h); false when none was kept.
  bool PairRestDepth(BodyId a, BodyId b, double* rest) const;
  void Commit();
  void Clear();
  size_t size() const { return current_.size(); }
  // The committed anchors, bit for bit, for snapshots; Load fails on
  // truncated or trailing bytes and then leaves the anchors as they were.
  void Save(ByteWriter* out) const;
  bool Load(ByteReader* in);

 private:
  using Key = std::tuple<BodyId, BodyId, uint32_t>;
  static Key MakeKey(const Contact& c) { return {std::min(c.id_a, c.id_b), std::max(c.id_a, c.id_b), c.feature_id}; }
  std::map<Key, AnchorState> current_;
  std::map<Key, AnchorState> next_;
};

// The stretch moved onto the tangent plane of n with its length kept (the
// contact frame turns a little between steps).
Vec3 ProjectStretch(const Vec3& stretch, const Vec3& n);

// Limits `trial` to the disk |f| <= limit; *sliding tells whether it was cut.
Vec3 CoulombLimit(const Vec3& trial, double limit, bool* sliding);

}  // namespace contactsim
