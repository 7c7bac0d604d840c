// Drake's Schunk WSG gripper driver, simulated: a model's two prismatic
// fingers (wsg_fingers.h) answer lcmt_schunk_wsg_command and report
// lcmt_schunk_wsg_status, so that a Drake controller (SchunkWsgCommandSender
// and SchunkWsgStatusReceiver) drives it unchanged (docs/actuators.md,
// "Drake's Schunk WSG gripper").
//
// A command's separation d and force F become each finger's position drive
// (physics/joint_actuator.h): the target q = s d / 2 (half the separation,
// on the finger's opening side s), the configured kp and kd, and the effort
// limit F, so that a finger closing on an object presses it with at most F
// and an object held between both is squeezed with F, the grip force a
// real WSG's force limit sets. (Drake's own simulated WSG,
// SchunkWsgPdController, saturates the difference of the two finger forces
// at F instead, which squeezes with F / 2 and reports F.) A model file's
// effort limit below F caps it, as a gripper's firmware caps a force above
// its rating; the status reports what was applied. The file's velocity
// limit is not put on the drives: a drive clamps the rate it asks for
// (physics/joint_actuator.h), which on a finger stalled against an object
// would cap the force at (h kp + kd) velocity_limit (17.5 N with the
// default gains, a 0.5 m/s limit and a 1/240 s step) instead of F. A
// finger's speed is bounded by its force limit instead.
//
// As the arm driver's, everything a command sets lives on the joints'
// actuators in the world, so snapshots, REWIND and the journal's replay
// carry the gripper; the driver keeps only the time of its last status.
#pragma once

#include "service/physics/world.h"
#include "service/server/arm_driver/status_clock.h"
#include "service/server/arm_driver/wsg_command.h"
#include "service/server/arm_driver/wsg_driver_config.h"
#include "service/server/arm_driver/wsg_fingers.h"
#include "service/server/arm_driver/wsg_status_builder.h"

namespace contactsim {

class WsgDriver {
 public:
  explicit WsgDriver(WsgDriverConfig config) : config_(std::move(config)), status_clock_(config_.status_rate_hz) {}
  const WsgDriverConfig& config() const { return config_; }

  // Holds each finger where it stands with the configured gains and the
  // default force (kDefaultWsgForce), as Drake's SchunkWsgCommandReceiver
  // starts before its first message.
  Status Hold(World* world) const;
  // One command on the fingers' drives. A separation outside the fingers'
  // range (wsg_fingers.h) or a missing gripper is refused and nothing
  // changes.
  Status Apply(const WsgCommand& cmd, World* world) const;

  // True once per status period of simulated time (status_clock.h).
  bool StatusDue(double time) { return status_clock_.Due(time); }
  // The gripper now: the separation and its rate, and the grip force, the
  // mean of the two drives' efforts of the last step towards closing.
  Status Read(const World& world, WsgReading* out) const;

 private:
  Status Find(const World& world, WsgFingers* fingers) const;
  // Sets both fingers' drives to the targets q[i] with the effort limit
  // `force` (capped by the file's), after checking both.
  Status SetDrives(const WsgFingers& fingers, const double (&q)[2], double force, World* world) const;

  const WsgDriverConfig config_;
  StatusClock status_clock_;
};

}  // namespace contactsim
