// When a driver's status is due: once per period of simulated time, the way
// Drake's drivers publish at a fixed rate (arm_driver.h, wsg_driver.h).
#pragma once

#include <cmath>
#include <cstdint>

namespace contactsim {

class StatusClock {
 public:
  explicit StatusClock(double rate_hz) : rate_hz_(rate_hz) {}
  // True at the first call, then whenever `time` (s) enters a new period of
  // 1 / rate_hz (after a REWIND too, when time goes back).
  bool Due(double time) {
    // a margin of 1e-6 period: a sum of steps that should land on a period
    // boundary may land a rounding error short of it
    const auto period = static_cast<int64_t>(std::floor(time * rate_hz_ + 1e-6));
    if (period == last_period_) return false;
    last_period_ = period;
    return true;
  }

 private:
  double rate_hz_;
  int64_t last_period_ = -1;
};

}  // namespace contactsim
