#include "service/server/arm_driver/wsg_status_builder.h"

#include <cmath>
#include <string>

namespace contactsim {

Status BuildWsgStatus(double sim_time_s, const WsgReading& in, drake::lcmt_schunk_wsg_status* out) {
  if (!std::isfinite(sim_time_s) || sim_time_s < 0) {
    return Status::InvalidArgument("sim_time_s must be finite and >= 0, got " + std::to_string(sim_time_s));
  }
  const double values[] = {in.separation, in.speed, in.force};
  const char* names[] = {"separation", "speed", "force"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(values[i])) return Status::InvalidArgument(std::string(names[i]) + " is not finite");
  }
  drake::lcmt_schunk_wsg_status m;
  m.utime = std::llround(sim_time_s * 1e6);
  m.actual_position_mm = in.separation * 1e3;
  m.actual_speed_mm_per_s = in.speed * 1e3;
  m.actual_force = std::abs(in.force);
  *out = m;
  return Status::Ok();
}

}  // namespace contactsim
