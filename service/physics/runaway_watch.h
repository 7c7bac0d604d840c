// Detects a world that blew up: a state that is not finite, or mechanical
// energy far beyond what the world had and what its inputs supplied since.
//
// Ideal joints and contacts do no work, so the mechanical energy E = T + V
// of the dynamic bodies (kinetic plus gravitational, World's KineticEnergy
// and PotentialEnergy) can only grow by the work of the applied wrenches,
// of moving kinematic bodies, and of the small elastic energy that
// compliant contacts and overlap push-out release. A step is a blow-up when
//   E - E_base - W  >  factor * S,
//   S = T_base + sum m (1/2 v_s^2 + |g| l_s)
// where E_base and T_base are the energies at the baseline (the last time a
// command changed the world), W sums the work of the wrenches since
// (F . dx + tau . w dt per step) and the bound 2 m V^2 of what a kinematic
// body moving at V can give each dynamic body it meets, and S is the
// scene's own energy scale: its motion plus every body moving at v_s = 1 m/s
// and falling l_s = 1 m. A solver that diverges grows E geometrically, so it
// passes any such bound within a few steps, while the largest gain a method
// shows in the random scenes (docs/physics.md, "Random scenes") is below a
// percent of S.
#pragma once

#include <string>

#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

class RunawayWatch {
 public:
  static constexpr double kDefaultFactor = 100.0;

  explicit RunawayWatch(double factor = kDefaultFactor) : factor_(factor) {}

  // Starts the account from the world as it is (after a command changed it).
  void Rebase(const World& world);
  // Before a step: the positions the step's work is measured from.
  void BeforeStep(const World& world);
  // After the step: OK, or kFailedPrecondition with a message that names the
  // step, the first body whose state is not finite or the fastest body, and
  // the energy against its bound.
  Status AfterStep(const World& world);

  double factor() const { return factor_; }

 private:
  double factor_;
  bool based_ = false;
  double base_energy_ = 0.0;  // J, E at the baseline
  double scale_ = 0.0;        // J, S
  double work_ = 0.0;         // J, W since the baseline
  std::vector<Vec3> before_;  // positions of the bodies before the step
};

}  // namespace contactsim
