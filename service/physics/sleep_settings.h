// When a settled island of bodies goes to sleep (docs/physics.md,
// "Sleeping"): every body of the island has stayed below both speeds for
// `time_to_sleep`. The defaults are Box2D's (v3 `b2_defaultSleepThreshold`
// 0.05 m/s with one length unit per metre; v2.4 `b2_angularSleepTolerance`
// 2 degrees/s and `b2_timeToSleep` 0.5 s): a box at rest under any of our
// methods moves far slower (its speed is the solver's residual, below
// 1e-3 m/s), a body that is still moving on purpose faster.
#pragma once

namespace contactsim {

struct SleepSettings {
  bool enabled = false;            // off in a bare World; the server's `sleep` setting turns it on
  double linear_speed = 0.05;      // m/s, of the centre of mass
  double angular_speed = 0.0349066;// rad/s (2 degrees/s)
  double time_to_sleep = 0.5;      // s below both speeds before the island sleeps
};

}  // namespace contactsim
