// Drake's lcmt_panda_status for one instant of a simulated arm: what a Drake
// controller (PandaStatusReceiver) reads from a Franka Panda driver
// (docs/actuators.md, "Drake's arm driver").
#pragma once

#include <drake/lcmt_panda_status.hpp>

#include "service/physics/status.h"
#include "service/server/arm_driver/arm_readings.h"

namespace contactsim {

// Fills *out for simulated time sim_time_s (s, >= 0). The fields follow
// libfranka's RobotState, as Drake's driver fills them; the simulation's
// are exact:
//   utime, robot_utime          sim_time_s in microseconds, rounded
//   joint_position              position (RobotState q)
//   joint_position_desired      position_commanded (q_d)
//   joint_velocity              velocity, the true rate (dq)
//   joint_velocity_desired      velocity_commanded, or zeros (dq_d)
//   joint_acceleration_desired  zeros: the drives are given no acceleration
//                               target (ddq_d)
//   joint_torque                torque_applied, or torque_commanded when it is
//                               empty (tau_J, the joint torque sensors)
//   joint_torque_desired        torque_commanded, gravity excluded as the
//                               arm's own compensation carries it (tau_J_d)
//   joint_torque_external       torque_external, or zeros (tau_ext_hat_filtered)
//   control_command_success_rate  1: every command is applied at the next
//                               step boundary, none arrives late
//   robot_mode                  kMove while the drives act on any input, else kIdle
//   control_mode                inputs as CONTROL_MODE_* bits
// Refuses what CheckArmReadings refuses; *out is untouched then.
Status BuildPandaStatus(double sim_time_s, const ArmJointReadings& in, drake::lcmt_panda_status* out);

}  // namespace contactsim
