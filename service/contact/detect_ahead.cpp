#include "service/contact/detect_ahead.h"

#include <algorithm>
#include <set>
#include <vector>

#include "service/collision/motion_bound.h"
#include "service/collision/narrowphase.h"

namespace contactsim {

void DetectAhead(const World& world, CollisionDetector& detector, double margin, double dt, ContactSet* contacts) {
  detector.Detect(world, margin, dt, contacts);
  const auto& bodies = world.bodies();
  std::set<BodyPair> fast;
  std::vector<double> reach;
  std::vector<BodyMotion> motion(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) motion[i] = MotionOf(bodies[i]);
  for (const BodyPair& p : detector.pairs()) {
    const double r = ClosingSpeedBound(motion[p.first], motion[p.second], dt) * dt;
    if (r <= margin) continue;
    fast.insert(p);
    reach.push_back(r);
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
