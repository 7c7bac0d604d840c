#include "service/collision/collision_detector.h"

#include <algorithm>

#include "service/collision/narrowphase.h"

namespace contactsim {

CollisionDetector::CollisionDetector() { CreateBroadphase("sap", &broadphase_); }

Status CollisionDetector::SetBroadphase(const std::string& name) {
  std::unique_ptr<Broadphase> next;
  Status status = CreateBroadphase(name, &next);
  if (!status.ok()) return status;
  broadphase_ = std::move(next);
  return Status::Ok();
}

void CollisionDetector::Detect(const World& world, double margin, double sweep_dt, ContactSet* contacts) {
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  boxes_.resize(n);
  movable_.resize(n);
  for (int i = 0; i < n; ++i) {
    boxes_[i] = ComputeAabb(bodies[i], margin, sweep_dt);
    movable_[i] = bodies[i].IsDynamic();
  }
  broadphase_->FindPairs(boxes_, movable_, &pairs_);
  DropJointedPairs(world);
  contacts->clear();
  for (const BodyPair& p : pairs_) {
    narrowphase_.Collide(bodies[p.first], p.first, bodies[p.second], p.second, margin, contacts);
  }
  stats_.candidate_pairs = static_cast<int>(pairs_.size());
  stats_.contacts = static_cast<int>(contacts->size());
}

void CollisionDetector::DropJointedPairs(const World& world) {
  if (world.joints().empty()) return;
  jointed_.clear();
  for (const Joint& j : world.joints()) {
    if (j.body_b == kWorldBody) continue;
    const int a = world.IndexOf(j.body_a), b = world.IndexOf(j.body_b);
    jointed_.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(jointed_.begin(), jointed_.end());
  pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(),
                              [this](const BodyPair& p) {  // first < second, as jointed_
                                return std::binary_search(jointed_.begin(), jointed_.end(), p);
                              }),
               pairs_.end());
}

}  // namespace contactsim
