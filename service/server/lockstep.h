// Lockstep co-simulation: registered controllers each send their input for
// step k (forces and torques on bodies, or "no input") before the server
// takes step k; the server publishes STATE k-1 and waits (docs/lockstep.md).
//
// A controller that is late (no input for k after its timeout of wall-clock
// time) is handled by its policy: kWait keeps waiting, kReuse applies its
// last input again, kDrop releases it. The policy changes which input a step
// gets, never how the step is computed: the inputs actually applied are what
// the journal records, so a replay is exact whatever the timing was.
//
// Plain data, no LCM and no clock: the simulation thread feeds it inputs and
// the time it has waited, so it is tested without threads.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/rigid_body.h"
#include "service/physics/status.h"
#include "service/server/actuator_update.h"

namespace contactsim {

enum class LatePolicy { kWait = 1, kReuse = 2, kDrop = 3 };
const char* LatePolicyName(LatePolicy policy);
// Parses "wait" / "reuse" / "drop".
Status ParseLatePolicy(const std::string& text, LatePolicy* policy);

struct BodyInput {
  BodyId body = 0;
  Vec3 force = Vec3::Zero();   // N, world, at the centre of mass
  Vec3 torque = Vec3::Zero();  // N m, world
};

struct ControllerInput {
  std::string controller;
  int64_t request_id = 0;
  int64_t step = 0;            // the step it is for
  std::vector<BodyInput> bodies;  // empty: no input
  ActuatorUpdate joints;          // for this step only; empty: none
};

class Lockstep {
 public:
  Status Register(const std::string& id, LatePolicy policy, double timeout_s);
  Status Release(const std::string& id);
  void Clear() { controllers_.clear(); }
  bool active() const { return !controllers_.empty(); }
  size_t size() const { return controllers_.size(); }

  // Queues an input (a second one for the same step replaces the first);
  // refuses one from an unregistered client or for a step that is already
  // taken (`next_step` is the step the server takes next), except a resend
  // of the input applied last (same step and request id), which is ignored.
  Status Offer(ControllerInput input, int64_t next_step);
  // True when every controller has an input queued for `step`.
  bool Ready(int64_t step) const;
  // Applies the late policies after `waited_s` of waiting for `step`;
  // returns one log line per decision (a reuse, a drop).
  std::vector<std::string> ResolveLate(int64_t step, double waited_s);
  // Seconds of waiting after which ResolveLate can decide something
  // (the smallest timeout of a non-waiting controller), or a negative
  // number when every missing controller waits forever.
  double NextDeadline(int64_t step) const;
  // Removes and returns the inputs for `step`, in controller id order.
  std::vector<ControllerInput> Take(int64_t step);

  int64_t late_events() const { return late_events_; }
  const std::string& last_late_event() const { return last_late_event_; }
  // "id (policy, timeout s, late n)" per controller, for STATUS.
  std::string Describe() const;

 private:
  struct Controller {
    LatePolicy policy = LatePolicy::kWait;
    double timeout_s = 0.1;
    std::map<int64_t, ControllerInput> queued;  // by step
    ControllerInput last;                       // last applied
    int64_t late = 0;
  };
  std::map<std::string, Controller> controllers_;  // ordered: deterministic application order
  int64_t late_events_ = 0;
  std::string last_late_event_;
};

// 64-bit FNV-1a over the applied inputs (controller, step, bodies, forces and
// torques), 0 when there were none; carried by STATE as input_digest.
uint64_t DigestInputs(const std::vector<ControllerInput>& inputs);

}  // namespace contactsim
