// Sleeping islands around any contact method (docs/physics.md, "Sleeping";
// docs/architecture.md, "Sleeping"). A settled world costs almost nothing,
// as in Box2D, Bullet and Jolt, without a change to any method:
//  1. wake: before the solve, each awake dynamic or moving kinematic body's
//     box, grown by kWakeMargin and swept by its motion over the step, is
//     tested against the boxes of the sleeping bodies (a broadphase); an
//     overlap wakes the sleeper's island, so no awake body ever meets a
//     sleeping one unanswered. A joint from a sleeping body to a moving
//     kinematic one wakes it too;
//  2. freeze: each sleeping body is presented to the method as a static
//     body (MotionType::kStatic, zero mass and inertia), and the joints of
//     sleeping bodies are held back. Every method and the integrator skip
//     static bodies, and the broadphase skips a pair of two non-dynamic
//     bodies, so two sleeping bodies (or a sleeping body and the ground)
//     cost no narrowphase and no solver row;
//  3. the method's Step;
//  4. thaw: the sleeping bodies get their mass back, the joints return;
//  5. settle: each awake dynamic body's rest timer grows by dt while its
//     speeds stay below the thresholds (and no wrench or moving kinematic
//     body drives it), else restarts at 0; an island (islands.h) whose
//     bodies have all rested for sleep.time_to_sleep falls asleep: P = L = 0,
//     each body labelled with the island's first body id. A contact the
//     method found between an awake and a sleeping body (a method margin
//     wider than kWakeMargin) wakes that island for the next step;
//  6. keep: the contacts of the bodies that fell asleep are kept, as the
//     method left them, and appended to each step's contacts while those
//     bodies sleep, so that a sleeping box still shows the contacts that
//     carry its weight (as Box2D keeps a sleeping island's contacts).
// With world.sleep.enabled false, Step is exactly method.Step.
#pragma once

#include <memory>
#include <vector>

#include "service/collision/broadphase.h"
#include "service/collision/collision_detector.h"
#include "service/contact/contact_method.h"
#include "service/physics/world.h"

namespace contactsim {

// m, grown around every wake box: twice the widest default detection margin
// of the methods (soft and xpbd: 0.01 m), so that a method's contact search
// never reaches a sleeping body before the wake test has woken it.
inline constexpr double kWakeMargin = 0.02;

struct SleepStats {
  int sleeping = 0;     // bodies asleep after the step
  int woken = 0;        // bodies woken before the step by an awake body's box
  int fell_asleep = 0;  // bodies that fell asleep at the end of the step
  // sleeping bodies the method's contacts reached during the step, woken
  // after it (a method margin wider than kWakeMargin); 0 when the wake test
  // saw every meeting coming
  int woken_late = 0;
};

class IslandSleep {
 public:
  IslandSleep();
  // One step of `method` (contact_method.h) with sleeping islands.
  StepStats Step(World& world, ContactMethod& method, CollisionDetector& detector, ContactSet* contacts);
  const SleepStats& stats() const { return stats_; }
  // Forgets the kept contacts: call when the world is replaced (reset,
  // scene load, snapshot restore), whose ids may name other bodies.
  void Reset() { kept_.clear(); }

 private:
  void WakeTouched(World& world);
  void Freeze(World& world);
  void Thaw(World& world);
  void Settle(World& world, const ContactSet& contacts);
  void KeepSleepingContacts(const World& world, ContactSet* contacts);

  struct Frozen {
    int index;
    double mass, inv_mass;
    Mat3 inertia_body, inv_inertia_body;
  };
  std::unique_ptr<Broadphase> broadphase_;
  std::vector<Aabb> boxes_;
  std::vector<AabbSupport> supports_;  // per body: where its box's descent starts
  std::vector<bool> movable_;
  std::vector<BodyPair> pairs_;
  std::vector<BodyPair> near_;  // awake dynamic pairs whose wake boxes overlap: one island
  std::vector<Frozen> frozen_;
  std::vector<Joint> held_joints_;  // every joint, while those of sleeping bodies sit out
  bool holding_joints_ = false;
  ContactSet kept_;  // of sleeping bodies, as the step before they slept left them
  SleepStats stats_;
};

// Wakes the island of body `id` and of every sleeping body whose box
// (grown by kWakeMargin) overlaps id's: for a command that changes the body
// (pose, velocity, wrench, mass, material) or adds or removes it, so that
// what rested on it, or against it, answers the change.
void WakeTouching(World& world, BodyId id);

}  // namespace contactsim
