// Drake's iiwa driver, simulated: a model of the world answers
// lcmt_iiwa_command and reports lcmt_iiwa_status, so that a Drake controller
// (IiwaCommandSender, IiwaStatusReceiver) drives it unchanged
// (docs/actuators.md, "Drake's arm driver").
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

#include <drake/lcmt_iiwa_status.hpp>

#include <cstdint>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/contact_method.h"

#include "service/physics/world.h"
#include "service/server/arm_driver/arm_command.h"
#include "service/server/arm_driver/arm_driver_config.h"
#include "service/server/arm_driver/arm_joints.h"

namespace contactsim {

class ArmDriver {
 public:
  explicit ArmDriver(ArmDriverConfig config) : config_(std::move(config)) {}
  const ArmDriverConfig& config() const { return config_; }

  // Holds the arm where it stands: position targets at the joints' angles
  // with the configured gains, no torque, the state a robot's controller
  // starts in before its first command.
  Status Hold(World* world) const;
  // One command on the arm's drives. joint_position has one target per
  // joint (the drives track it with kp and kd) or none (torque only: the
  // gains are 0); joint_torque one feed-forward torque per joint or none
  // (zeros). A wrong count or a missing arm is refused and nothing changes.
  Status Apply(const ArmCommand& cmd, World* world) const;
  // Before every step: notes the world's external wrenches for the status's
  // external torques, then compensates the arm's weight (CompensateGravity)
  // when configured.
  void BeforeStep(World* world);

  // True once per status period of simulated time: at the first call, then
  // whenever `time` (s) enters a new period (after a REWIND too).
  bool StatusDue(double time);
  // The status of the arm now (iiwa_status_builder.h): the measured torque
  // is the drives' effort of the last step plus, with gravity compensation,
  // the torque holding the arm's weight, which the real arm's joint torque
  // sensors would carry; the external torque is that of the step's
  // `contacts` (values of `kind`) and of the wrenches noted before it
  // (arm_external_torque.h).
  Status BuildStatus(const World& world, const ContactSet& contacts, ContactValueKind kind,
                     drake::lcmt_iiwa_status* out) const;

 private:
  Status Find(const World& world, ArmJoints* arm) const;

  const ArmDriverConfig config_;
  int64_t last_status_period_ = -1;
  std::vector<TimedWrench> step_wrenches_;  // the world's, as the step under way began
};

}  // namespace contactsim
