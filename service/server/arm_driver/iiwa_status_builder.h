// Drake's lcmt_iiwa_status for one instant of a simulated arm: what a Drake
// controller reads from an iiwa driver (docs/protocol.md, "Drake's
// arm-driver messages").
#pragma once

#include <drake/lcmt_iiwa_status.hpp>

#include <vector>

#include "service/physics/status.h"

namespace contactsim {

// One reading of the arm's joints, each array in the arm's joint order with
// one entry per joint.
struct IiwaJointReadings {
  std::vector<double> position;            // rad, the joint angles now
  std::vector<double> velocity;            // rad/s, the joint rates now
  std::vector<double> position_commanded;  // rad, the last position target received
  std::vector<double> torque_commanded;    // N m, the torque the drives were asked for
  std::vector<double> torque_applied;      // N m, what the drives applied; empty: torque_commanded
  std::vector<double> torque_external;     // N m, joint torque from contacts; empty: zeros
};

// Fills *out for simulated time sim_time_s (s, >= 0). The simulation knows
// its state exactly, so the fields a real driver estimates are exact here:
//   utime                     sim_time_s in microseconds, rounded to the nearest
//                             (a sum of 5 ms steps must not read 1 us early)
//   joint_position_measured   position
//   joint_velocity_estimated  velocity: the true rate, where the real driver
//                             filters differences of positions
//   joint_position_commanded  position_commanded
//   joint_position_ipo        position_commanded: the simulated driver has no
//                             interpolator between the command and the drive
//                             (Drake's simulated sender leaves it zero)
//   joint_torque_commanded    torque_commanded
//   joint_torque_measured     torque_applied, or torque_commanded when it is
//                             empty, as Drake's simulated sender does
//   joint_torque_external     torque_external, or zeros
// Refuses (InvalidArgument, naming the field) an empty arm, arrays of
// different lengths, a non-finite value and a negative or non-finite time;
// *out is untouched then.
Status BuildIiwaStatus(double sim_time_s, const IiwaJointReadings& in, drake::lcmt_iiwa_status* out);

}  // namespace contactsim
