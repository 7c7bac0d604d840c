#include "service/contact/detect_ahead.h"

#include <algorithm>
#include <vector>

#include "service/collision/motion_bound.h"
#include "service/collision/narrowphase.h"

namespace contactsim {
namespace {

// pairs a thread bounds at a time
constexpr int kAheadPairGrain = 512;
// fast pairs a thread collides at a time (the detector's chunk of pairs)
constexpr int kFastPairGrain = 16;
// contacts a thread sorts into kept and fast at a time
constexpr int kContactGrain = 1024;

}  // namespace

// The fast pairs' contacts are collided again within each pair's reach,
// on the threads: each chunk of fast pairs into its own set, the sets
// joined in chunk order, so the contacts come out in the order of a serial
// loop over the pairs (ascending, as the detector's) for any thread count.
void DetectAhead(const World& world, CollisionDetector& detector, double margin, double dt, ContactSet* contacts) {
  detector.Detect(world, margin, dt, contacts);
  ParallelRunner& runner = detector.runner();
  const auto& bodies = world.bodies();
  const std::vector<BodyPair>& pairs = detector.pairs();
  // each body's terms of the bound once, then each pair's bound
  std::vector<BodyMotion> motion(bodies.size());
  runner.For(static_cast<int>(bodies.size()), kAheadPairGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) motion[i] = MotionOf(bodies[i]);
  });
  std::vector<double> pair_reach(pairs.size());
  runner.For(static_cast<int>(pairs.size()), kAheadPairGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      pair_reach[k] = ClosingSpeedBound(motion[pairs[k].first], motion[pairs[k].second], dt) * dt;
    }
  });
  // the fast pairs, ascending as the detector's pairs are
  std::vector<BodyPair> fast;
  std::vector<double> reach;
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (pair_reach[k] <= margin) continue;
    fast.push_back(pairs[k]);
    reach.push_back(pair_reach[k]);
  }
  if (fast.empty()) return;
  // which contacts belong to a fast pair (found again below)
  const int n = static_cast<int>(contacts->size());
  std::vector<char> refound(n);
  runner.For(n, kContactGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      const Contact& c = (*contacts)[i];
      refound[i] = std::binary_search(fast.begin(), fast.end(), BodyPair(std::min(c.a, c.b), std::max(c.a, c.b)));
    }
  });
  const int chunks = (static_cast<int>(fast.size()) + kFastPairGrain - 1) / kFastPairGrain;
  std::vector<ContactSet> found(chunks);
  runner.For(static_cast<int>(fast.size()), kFastPairGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      const BodyPair& p = fast[k];
      Collide(bodies[p.first], p.first, bodies[p.second], p.second, margin + reach[k], &found[k / kFastPairGrain]);
    }
  });
  ContactSet kept;
  kept.reserve(n);
  for (int i = 0; i < n; ++i) {
    if (!refound[i]) kept.push_back((*contacts)[i]);
  }
  for (const ContactSet& chunk : found) kept.insert(kept.end(), chunk.begin(), chunk.end());
  contacts->swap(kept);
}

}  // namespace contactsim
