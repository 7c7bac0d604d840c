#include "service/contact/sleep/island_sleep.h"

#include <algorithm>

#include "service/collision/aabb.h"
#include "service/physics/collision_filter.h"
#include "service/contact/sleep/islands.h"

namespace contactsim {
namespace {

bool Awake(const RigidBody& b) { return b.IsDynamic() && !b.asleep(); }

bool MovingKinematic(const RigidBody& b) {
  return b.motion == MotionType::kKinematic && (!b.kinematic_v.isZero(0.0) || !b.kinematic_w.isZero(0.0));
}

// The box a body could reach within dt: its bounds grown by kWakeMargin,
// swept by v dt, and grown by |w| r dt for the turn of its farthest point.
// `support` as the collision detector's: a hull's extreme vertices found by
// descent from the last ones, the same box as a scan over every vertex.
Aabb WakeBox(const RigidBody& b, double dt, AabbSupport* support) {
  Aabb box = ComputeAabb(b, kWakeMargin, dt, support);
  if (b.shape.type == ShapeType::kPlane) return box;
  const double r = 0.5 * (box.max - box.min).norm();
  box.Inflate(b.AngularVelocity().norm() * r * dt);
  return box;
}

bool Below(const RigidBody& b, const SleepSettings& s) {
  return b.LinearVelocity().squaredNorm() <= s.linear_speed * s.linear_speed &&
         b.AngularVelocity().squaredNorm() <= s.angular_speed * s.angular_speed;
}

}  // namespace

IslandSleep::IslandSleep() { CreateBroadphase("sap", &broadphase_); }

StepStats IslandSleep::Step(World& world, ContactMethod& method, CollisionDetector& detector, ContactSet* contacts) {
  if (!world.sleep.enabled) return method.Step(world, detector, contacts);
  stats_ = SleepStats{};
  WakeTouched(world);
  Freeze(world);
  const StepStats stats = method.Step(world, detector, contacts);
  Thaw(world);
  Settle(world, *contacts);
  KeepSleepingContacts(world, contacts);
  stats_.sleeping = world.SleepingCount();
  return stats;
}

// 1. wake the islands set moving from outside, and those an awake body's
// wake box reaches
void IslandSleep::WakeTouched(World& world) {
  near_.clear();
  auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  const int asleep_before = world.SleepingCount();
  if (asleep_before == 0) return;
  // a sleeping body holds P = L = 0; momentum means a caller set it moving
  // (the server wakes on every command, an in-process caller may not)
  for (RigidBody& b : bodies) {
    if (b.asleep() && (!b.P.isZero(0.0) || !b.L.isZero(0.0))) world.WakeIsland(b.sleep_island);
  }
  boxes_.resize(n);
  movable_.resize(n);
  supports_.resize(n);
  for (int i = 0; i < n; ++i) {
    boxes_[i] = WakeBox(bodies[i], world.dt, &supports_[i]);
    movable_[i] = Awake(bodies[i]) || MovingKinematic(bodies[i]);
  }
  // the broadphase skips pairs of two non-movable bodies: sleeping or static;
  // a filtered pair passes through each other, so it neither wakes nor joins
  broadphase_->FindPairs(boxes_, movable_, &pairs_);
  for (const auto& [i, j] : pairs_) {
    const RigidBody& a = bodies[i];
    const RigidBody& b = bodies[j];
    if (!ShouldCollide(a, b, world.joined_pairs())) continue;
    if (a.asleep() != b.asleep()) world.WakeIsland(a.asleep() ? a.sleep_island : b.sleep_island);
    if (a.IsDynamic() && b.IsDynamic()) near_.emplace_back(i, j);
  }
  for (const Joint& j : world.joints()) {
    if (j.body_b == kWorldBody) continue;
    const RigidBody* a = world.Find(j.body_a);
    const RigidBody* b = world.Find(j.body_b);
    if (a->asleep() && MovingKinematic(*b)) world.WakeIsland(a->sleep_island);
    if (b->asleep() && MovingKinematic(*a)) world.WakeIsland(b->sleep_island);
  }
  stats_.woken = asleep_before - world.SleepingCount();
}

// 2. present the sleeping bodies as static, and hold back their joints
void IslandSleep::Freeze(World& world) {
  frozen_.clear();
  auto& bodies = world.bodies();
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    RigidBody& b = bodies[i];
    if (!b.asleep()) continue;
    frozen_.push_back({i, b.mass, b.inv_mass, b.inertia_body, b.inv_inertia_body});
    b.MakeStatic();
  }
  holding_joints_ = false;
  if (frozen_.empty()) return;
  std::vector<Joint> awake;
  for (const Joint& j : world.joints()) {
    const RigidBody* b = j.body_b == kWorldBody ? nullptr : world.Find(j.body_b);
    if (world.Find(j.body_a)->asleep() || (b != nullptr && b->asleep())) continue;
    awake.push_back(j);
  }
  if (awake.size() == world.joints().size()) return;
  held_joints_ = world.joints();
  holding_joints_ = true;
  world.AssignJoints(std::move(awake), world.next_joint_id);  // a subset of valid joints: cannot fail
}

// 4. give the sleeping bodies their mass back
void IslandSleep::Thaw(World& world) {
  auto& bodies = world.bodies();
  for (const Frozen& f : frozen_) {
    RigidBody& b = bodies[f.index];
    b.motion = MotionType::kDynamic;
    b.mass = f.mass;
    b.inv_mass = f.inv_mass;
    b.inertia_body = f.inertia_body;
    b.inv_inertia_body = f.inv_inertia_body;
  }
  if (holding_joints_) world.AssignJoints(std::move(held_joints_), world.next_joint_id);
  holding_joints_ = false;
}

// 5. rest timers, and the islands that have rested long enough fall asleep
void IslandSleep::Settle(World& world, const ContactSet& contacts) {
  auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  const SleepSettings& s = world.sleep;
  // driven bodies cannot rest: a wrench acts, or a moving kinematic body
  // (a conveyor, a lift) carries them
  std::vector<char> driven(n, 0);
  for (const TimedWrench& w : world.wrenches()) {
    const int i = world.IndexOf(w.body);
    if (i >= 0) driven[i] = 1;
  }
  auto drive = [&](int a, int b) {
    if (a < 0 || b < 0) return;
    if (MovingKinematic(bodies[b])) driven[a] = 1;
    if (MovingKinematic(bodies[a])) driven[b] = 1;
  };
  const int asleep = world.SleepingCount();
  for (const Contact& c : contacts) {
    drive(c.a, c.b);
    // an awake body met a sleeping one beyond the wake test's reach
    if (bodies[c.a].asleep() && Awake(bodies[c.b])) world.WakeIsland(bodies[c.a].sleep_island);
    if (bodies[c.b].asleep() && Awake(bodies[c.a])) world.WakeIsland(bodies[c.b].sleep_island);
  }
  stats_.woken_late = asleep - world.SleepingCount();
  for (const Joint& j : world.joints()) {
    if (j.body_b != kWorldBody) drive(world.IndexOf(j.body_a), world.IndexOf(j.body_b));
  }
  for (int i = 0; i < n; ++i) {
    RigidBody& b = bodies[i];
    if (!Awake(b)) continue;
    b.rest_time = (!driven[i] && Below(b, s)) ? b.rest_time + world.dt : 0.0;
  }
  // an island sleeps when its least rested body has rested long enough
  const std::vector<int> root = FindIslands(world, contacts, near_);
  std::vector<double> least(n, 0.0);
  for (int i = 0; i < n; ++i) {  // a root comes before the rest of its island
    if (root[i] == i) least[i] = bodies[i].rest_time;
    else if (root[i] >= 0) least[root[i]] = std::min(least[root[i]], bodies[i].rest_time);
  }
  for (int i = 0; i < n; ++i) {
    if (root[i] < 0 || least[root[i]] < s.time_to_sleep) continue;
    RigidBody& b = bodies[i];
    b.sleep_island = bodies[root[i]].id;
    b.P.setZero();
    b.L.setZero();
    ++stats_.fell_asleep;
  }
}

// 6. list the contacts of the sleeping bodies as they slept
void IslandSleep::KeepSleepingContacts(const World& world, ContactSet* contacts) {
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  // a kept index still names its body unless bodies were removed since
  auto index_of = [&](int i, BodyId id) { return i >= 0 && i < n && bodies[i].id == id ? i : world.IndexOf(id); };
  // a contact is kept while every dynamic body of it sleeps
  auto sleeps = [&](int i) { return i >= 0 && (!bodies[i].IsDynamic() || bodies[i].asleep()); };
  const size_t fresh = contacts->size();
  size_t kept = 0;
  for (Contact& c : kept_) {
    c.a = index_of(c.a, c.id_a);
    c.b = index_of(c.b, c.id_b);
    if (sleeps(c.a) && sleeps(c.b)) kept_[kept++] = c;
  }
  kept_.resize(kept);
  contacts->insert(contacts->end(), kept_.begin(), kept_.end());
  for (size_t i = 0; i < fresh; ++i) {
    const Contact& c = (*contacts)[i];
    if (sleeps(c.a) && sleeps(c.b)) kept_.push_back(c);
  }
}

void WakeTouching(World& world, BodyId id) {
  const RigidBody* body = world.Find(id);
  if (body == nullptr) return;
  world.WakeBody(id);
  const Aabb box = ComputeAabb(*body, kWakeMargin, 0.0);
  std::vector<BodyId> islands;
  for (const RigidBody& b : world.bodies()) {
    if (b.asleep() && ComputeAabb(b, kWakeMargin, 0.0).Overlaps(box)) islands.push_back(b.sleep_island);
  }
  for (BodyId island : islands) world.WakeIsland(island);
}

}  // namespace contactsim
