// The soft step's contact manifolds packed into the float path's bundles
// (soft_wide_layout.h) and their impulses unpacked after the step.
//
// Colour c's manifolds (block_colours.h) fill its bundles `width` at a
// time, in their order; the overflow, which the double path sweeps in
// order on one thread, gets a bundle per manifold, swept in order too.
#pragma once

#include <vector>

#include "service/contact/block_colours.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/soft/soft_manifold.h"
#include "service/contact/soft/wide/soft_wide_layout.h"

namespace contactsim {

class WideBundles {
 public:
  // Packs `manifolds` (ordered colour by colour, as `colours` says) of
  // `points`, whose lambdas hold the warm start, for `width` lanes, their
  // friction acting at `friction_points` (null: at the points); `dummy` is
  // the resting body padding lanes read. What the points' rows derive
  // from their anchors is left to the prepare kernel (soft_wide_layout.h).
  void Pack(const std::vector<SoftPoint>& points, const std::vector<SoftManifold>& manifolds,
            const BlockColours& colours, const std::vector<SoftBody>& bodies,
            const std::vector<Vec3>* friction_points, int width, int dummy);
  // The accumulated impulses, largest pushes and step totals back into `points`.
  void Unpack(std::vector<SoftPoint>& points) const;
  // The friction rows' Jacobians, responses and effective masses the
  // prepare kernel computed, into `points`.
  void UnpackFrictionRows(std::vector<SoftPoint>& points) const;
  // Colour c's bundles are [colours().starts[c], starts[c + 1]); the
  // overflow's bundles follow, one manifold each.
  const BlockColours& colours() const { return colours_; }
  int bundles() const { return static_cast<int>(slots_.size()); }
  wide::WideView View(wide::WideBody* bodies);

 private:
  // Counts each bundle's slots, places the bundles and clears their fields.
  void Allocate(const std::vector<SoftManifold>& manifolds, const BlockColours& colours);
  const float* Aligned() const;
  // calls read(point, slot, lane's first float) for every packed point
  template <class Read>
  void ForEachPoint(const Read& read) const;
  template <int W>
  void UnpackLanes(std::vector<SoftPoint>& points) const;
  float* Aligned() { return const_cast<float*>(static_cast<const WideBundles*>(this)->Aligned()); }
  // W: the width, when it is known when compiling (4, 8), else 0 (width_)
  template <int W>
  void PackLane(const std::vector<SoftPoint>& points, const SoftManifold& m, const std::vector<SoftBody>& bodies,
                const std::vector<Vec3>* friction_points, int bundle, int lane);
  template <int W>
  void PackLanes(const std::vector<SoftPoint>& points, const std::vector<SoftManifold>& manifolds,
                 const BlockColours& colours, const std::vector<SoftBody>& bodies,
                 const std::vector<Vec3>* friction_points);
  // Zeroes slots [from, slots of the bundle) of a lane: no anchors, no
  // impulse (the prepare kernel gives them no mass: they push nothing).
  void ClearSlots(int bundle, int lane, int from);
  // A padding lane (it reads the resting dummy body): every field the
  // kernels read before the prepare kernel writes it, zero.
  void ClearLane(int bundle, int lane);

  int width_ = 0;
  int dummy_ = 0;
  bool friction_at_anchors_ = true;  // kFa, kFb not packed (the kernels read kRa, kRb)
  std::vector<float> data_;  // from its first kAlign-aligned float (Aligned)
  std::vector<int> body_a_, body_b_;            // per lane
  std::vector<unsigned char> write_a_, write_b_;  // per lane
  std::vector<unsigned char> slots_;            // per bundle
  std::vector<int> offsets_;                    // per bundle: its first float after Aligned()
  std::vector<int> points_;                     // per lane and slot: the point, or -1
  BlockColours colours_;
};

}  // namespace contactsim
