// Drake's arm drivers, simulated: a model of the world answers the commands
// of Drake's iiwa or Franka Panda driver protocol and reports its status
// (arm_protocol.h), so that a Drake controller (IiwaCommandSender and
// IiwaStatusReceiver, PandaCommandSender and PandaStatusReceiver) drives it
// unchanged (docs/actuators.md, "Drake's arm driver").
//
// Everything a command sets lives in the world, on the arm's joints'
// actuators (physics/joint_actuator.h): the position targets, the gains
// and the feed-forward torques. The driver keeps no state of its own but
// the time of its last status and the external wrenches of the step under
// way (read again every step), so snapshots, REWIND and the journal's
// replay carry the arm as they carry any other joint.
//
// The simulation thread owns the driver, as it owns the world.
#pragma once

#include <cstdint>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/contact_method.h"

#include "service/physics/world.h"
#include "service/server/arm_driver/arm_command.h"
#include "service/server/arm_driver/arm_driver_config.h"
#include "service/server/arm_driver/arm_joints.h"
#include "service/server/arm_driver/arm_protocol.h"
#include "service/server/arm_driver/arm_readings.h"
#include "service/server/arm_driver/status_clock.h"

namespace contactsim {

class ArmDriver {
 public:
  explicit ArmDriver(ArmDriverConfig config)
      : config_(std::move(config)),
        protocol_(FindArmProtocol(config_.protocol)),
        status_clock_(config_.status_rate_hz) {}
  const ArmDriverConfig& config() const { return config_; }
  // The config's protocol; null when it names none (a config not read by
  // ReadArmDriverConfig), which StartArmDriver refuses.
  const ArmProtocol* protocol() const { return protocol_; }

  // Holds the arm where it stands: position targets at the joints' angles
  // with the configured gains, no torque, the state a robot's controller
  // starts in before its first command.
  Status Hold(World* world) const;
  // One command on the arm's drives. Each array has one entry per joint or
  // none. With positions, the drives track them with kp and kd, towards the
  // velocities when given, else at rest; with velocities only, they track
  // those with kd (kp = 0); with neither the gains are 0 (torque only). The
  // torques are the feed-forward (none: zeros). A wrong count or a missing
  // arm is refused and nothing changes.
  Status Apply(const ArmCommand& cmd, World* world) const;
  // Before every step: notes the world's external wrenches for the status's
  // external torques, then compensates the arm's weight (CompensateGravity)
  // when configured.
  void BeforeStep(World* world);

  // True once per status period of simulated time (status_clock.h).
  bool StatusDue(double time) { return status_clock_.Due(time); }
  // The reading of the arm now, which the protocol's status reports
  // (arm_readings.h): the commanded values are the drives'; the applied
  // torque is the drives' effort of the last step plus, with gravity
  // compensation, the torque holding the arm's weight, which the real arm's
  // joint torque sensors would carry; the external torque is that of the
  // step's `contacts` (values of `kind`) and of the wrenches noted before it
  // (arm_external_torque.h).
  Status Read(const World& world, const ContactSet& contacts, ContactValueKind kind, ArmJointReadings* out) const;

 private:
  Status Find(const World& world, ArmJoints* arm) const;

  const ArmDriverConfig config_;
  const ArmProtocol* const protocol_;
  StatusClock status_clock_;
  std::vector<TimedWrench> step_wrenches_;  // the world's, as the step under way began
};

}  // namespace contactsim
