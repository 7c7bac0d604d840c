#include "service/contact/detect_ahead.h"

#include <algorithm>
#include <set>
#include <vector>

#include "service/collision/motion_bound.h"
#include "service/collision/narrowphase.h"

namespace contactsim {
namespace {

// pairs a thread bounds at a time
constexpr int kAheadPairGrain = 512;

}  // namespace

void DetectAhead(const World& world, CollisionDetector& detector, double margin, double dt, ContactSet* contacts) {
  detector.Detect(world, margin, dt, contacts);
  const auto& bodies = world.bodies();
  const std::vector<BodyPair>& pairs = detector.pairs();
  // each body's terms of the bound once, then each pair's bound
  std::vector<BodyMotion> motion(bodies.size());
  detector.runner().For(static_cast<int>(bodies.size()), kAheadPairGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) motion[i] = MotionOf(bodies[i]);
  });
  std::vector<double> pair_reach(pairs.size());
  detector.runner().For(static_cast<int>(pairs.size()), kAheadPairGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      pair_reach[k] = ClosingSpeedBound(motion[pairs[k].first], motion[pairs[k].second], dt) * dt;
    }
  });
  std::set<BodyPair> fast;
  std::vector<double> reach;
  for (size_t k = 0; k < pairs.size(); ++k) {
    if (pair_reach[k] <= margin) continue;
    fast.insert(pairs[k]);
    reach.push_back(pair_reach[k]);
  }
  if (fast.empty()) return;
  ContactSet kept;
  for (const Contact& c : *contacts) {
    if (!fast.count({std::min(c.a, c.b), std::max(c.a, c.b)})) kept.push_back(c);
  }
  size_t k = 0;
  for (const BodyPair& p : fast) {
    Collide(bodies[p.first], p.first, bodies[p.second], p.second, margin + reach[k++], &kept);
  }
  contacts->swap(kept);
}

}  // namespace contactsim
