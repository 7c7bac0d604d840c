// Drake's lcmt_iiwa_status for one instant of a simulated arm: what a Drake
// controller reads from an iiwa driver (docs/protocol.md, "Drake's
// arm-driver messages").
#pragma once

#include <drake/lcmt_iiwa_status.hpp>

#include "service/physics/status.h"
#include "service/server/arm_driver/arm_readings.h"

namespace contactsim {

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
// The iiwa's protocol has no velocity target: velocity_commanded and inputs
// are not sent. Refuses what CheckArmReadings refuses; *out is untouched
// then.
Status BuildIiwaStatus(double sim_time_s, const ArmJointReadings& in, drake::lcmt_iiwa_status* out);

}  // namespace contactsim
