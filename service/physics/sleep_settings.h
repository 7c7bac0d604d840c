// When a settled island of bodies goes to sleep (docs/physics.md,
// "Sleeping"): every body of the island has stayed below both speeds for
// `time_to_sleep`. The defaults are Box2D's (v3 `b2_defaultSleepThreshold`
// 0.05 m/s with one length unit per metre; v2.4 `b2_angularSleepTolerance`
// 2 degrees/s and `b2_timeToSleep` 0.5 s). A box dropped 5 cm onto the
// ground drops below both speeds within a few steps of landing under every
// method (each puts it to sleep 0.50 to 0.52 s after it lands,
// tests/contact/island_sleep_test.cpp), while a swinging pendulum stays
// below them for 3 steps at most at its turning points.
#pragma once

namespace contactsim {

struct SleepSettings {
  bool enabled = false;              // off in a bare World; the server's `sleep` setting turns it on
  double linear_speed = 0.05;        // m/s, of the centre of mass
  double angular_speed = 0.0349066;  // rad/s (2 degrees/s)
  double time_to_sleep = 0.5;        // s below both speeds before the island sleeps
};

}  // namespace contactsim
