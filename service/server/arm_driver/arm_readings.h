// One reading of a simulated arm's joints, the protocol-neutral content of
// every arm driver's status (iiwa_status_builder.h, panda_status_builder.h),
// and the check each status builder makes of it.
#pragma once

#include <vector>

#include "service/physics/status.h"

namespace contactsim {

// Which inputs the arm's drives act on now (physics/joint_actuator.h).
enum ArmInputs : int {
  kArmPositionInput = 1,  // position targets, kp > 0
  kArmVelocityInput = 2,  // velocity targets: kp = 0 and kd > 0, or a non-zero target with kp > 0
  kArmTorqueInput = 4,    // a non-zero feed-forward torque
};

// Each array in the arm's joint order with one entry per joint.
struct ArmJointReadings {
  std::vector<double> position;            // rad, the joint angles now
  std::vector<double> velocity;            // rad/s, the joint rates now
  std::vector<double> position_commanded;  // rad, the last position target received
  std::vector<double> velocity_commanded;  // rad/s, the velocity target; empty: zeros
  std::vector<double> torque_commanded;    // N m, the torque the drives were asked for
  std::vector<double> torque_applied;      // N m, what the drives applied; empty: torque_commanded
  std::vector<double> torque_external;     // N m, joint torque from contacts; empty: zeros
  int inputs = 0;                          // ArmInputs bits
};

// InvalidArgument, naming the field, for a negative or non-finite time
// (s), an empty arm, arrays of different lengths or a non-finite value.
Status CheckArmReadings(double sim_time_s, const ArmJointReadings& in);

// An optional array: `values`, or n zeros when it is empty.
std::vector<double> OrZeros(const std::vector<double>& values, size_t n);

}  // namespace contactsim
