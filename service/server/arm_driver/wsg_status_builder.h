// Drake's lcmt_schunk_wsg_status for one instant of a simulated gripper:
// what a Drake controller (SchunkWsgStatusReceiver) reads from a Schunk WSG
// driver (docs/actuators.md, "Drake's Schunk WSG gripper").
#pragma once

#include <drake/lcmt_schunk_wsg_status.hpp>

#include "service/physics/status.h"

namespace contactsim {

// One reading of the gripper (WsgDriver::Read).
struct WsgReading {
  double separation = 0;  // m, between the fingers
  double speed = 0;       // m/s, the separation's rate
  double force = 0;       // N, the grip force the finger drives applied, >= 0
};

// Fills *out for simulated time sim_time_s (s, >= 0):
//   utime                  sim_time_s in microseconds, rounded to the nearest
//   actual_position_mm     separation in mm
//   actual_speed_mm_per_s  speed in mm/s
//   actual_force           force, positive as Drake's simulated sender
//                          reports it (SchunkWsgStatusSender takes abs())
// InvalidArgument, naming the field, for a negative or non-finite time or a
// non-finite reading; *out is untouched then.
Status BuildWsgStatus(double sim_time_s, const WsgReading& in, drake::lcmt_schunk_wsg_status* out);

}  // namespace contactsim
