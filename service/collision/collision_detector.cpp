#include "service/collision/collision_detector.h"

#include <algorithm>

#include "service/collision/narrowphase.h"
#include "service/physics/collision_filter.h"

namespace contactsim {
namespace {

// Bodies per parallel task, at least: a box costs ~50 ns, a oneTBB task ~1 us.
// 128 lets a 211-box pyramid use two threads.
constexpr int kBodyGrain = 128;
// Pairs a thread filters at a time: two bodies' filters read far apart.
constexpr int kFilterGrain = 1024;

}  // namespace

CollisionDetector::CollisionDetector() : runner_(std::make_unique<ParallelRunner>(1)) {
  CreateBroadphase("sap", &broadphase_);
}

Status CollisionDetector::SetThreads(int threads) {
  Status status = CheckThreadCount(threads);
  if (!status.ok()) return status;
  if (threads != runner_->threads()) runner_ = std::make_unique<ParallelRunner>(threads);
  return Status::Ok();
}

Status CollisionDetector::SetBroadphase(const std::string& name) {
  std::unique_ptr<Broadphase> next;
  Status status = CreateBroadphase(name, &next);
  if (!status.ok()) return status;
  broadphase_ = std::move(next);
  return Status::Ok();
}

void CollisionDetector::Detect(const World& world, double margin, double sweep_dt, ContactSet* contacts) {
  ComputeBoxes(world, margin, sweep_dt);
  broadphase_->SetRunner(runner_.get());
  broadphase_->FindPairs(boxes_, movable_, &pairs_);
  DropFilteredPairs(world);
  contacts->clear();
  narrowphase_.CollidePairs(world.bodies(), pairs_, margin, *runner_, contacts);
  stats_.candidate_pairs = static_cast<int>(pairs_.size());
  stats_.contacts = static_cast<int>(contacts->size());
  ++stats_.detections;
}

void CollisionDetector::ComputeBoxes(const World& world, double margin, double sweep_dt) {
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  boxes_.resize(n);
  movable_.resize(n);
  supports_.resize(n);
  // each body writes its own box; movable_ is a vector<bool>, whose bits
  // share words, so it is filled on this thread
  runner_->For(n, kBodyGrain, [&](int begin, int end, int /*worker*/) {
    for (int i = begin; i < end; ++i) boxes_[i] = ComputeAabb(bodies[i], margin, sweep_dt, &supports_[i]);
  });
  for (int i = 0; i < n; ++i) movable_[i] = bodies[i].IsDynamic();
}

void CollisionDetector::DropFilteredPairs(const World& world) {
  const auto& bodies = world.bodies();
  const JointPairSet& joined = world.joined_pairs();
  // each pair's verdict on the threads, then the kept pairs packed in order
  const int n = static_cast<int>(pairs_.size());
  std::vector<char> keep(n);
  runner_->For(n, kFilterGrain, [&](int begin, int end, int /*worker*/) {
    for (int i = begin; i < end; ++i) keep[i] = ShouldCollide(bodies[pairs_[i].first], bodies[pairs_[i].second], joined);
  });
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    if (keep[i]) pairs_[kept++] = pairs_[i];
  }
  pairs_.resize(kept);
}

}  // namespace contactsim
