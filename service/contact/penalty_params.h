// Parameters of the penalty method (penalty_method.h), with units, defaults
// and ranges. ParsePenaltyParams validates a whole ParamMap before changing
// anything, so a bad value leaves the old parameters in place.
#pragma once

#include <string>

#include "service/contact/contact_method.h"

namespace contactsim {

struct PenaltyParams {
  // normal force law: "linear" spring-dashpot or "hunt_crossley"
  std::string model = "linear";
  double kp = 1.0e6;              // N/m (N/m^n for hunt_crossley): pair stiffness
  double kd = 1.0e3;              // N s/m: pair damping, used when restitution = "off"
  // Damping source: "material" derives kd (linear) or the Hunt-Crossley
  // alpha from the pair's combined material restitution, a number in [0, 1]
  // derives it from that value, "off" uses kd / hc_damping as given.
  std::string restitution = "material";
  double hc_exponent = 1.5;       // n of kp d^n (1.5: Hertz contact of spheres)
  double hc_damping = 0.2;        // s/m: Hunt-Crossley alpha when restitution = "off"
  double friction_stiffness = 1.0e6;      // N/m: tangential spring of a pair
  double friction_damping_ratio = 1.0;    // unitless: of the tangential spring, 1 = critical
  std::string integrator = "implicit";    // explicit | implicit
  double theta = 1.0;             // implicit: 1 = linearly implicit Euler, 0.5 = trapezoidal
  int substeps = 1;               // steps of dt / substeps per world step
  int iterations = 20;            // implicit: active-set passes at most
  double margin = 0.005;          // m: contacts up to this gap are detected (implicit: predicted)

  // the restitution as a number, or -1 for "material" / "off"
  double RestitutionValue() const;
};

// Reads `params` over a copy of `current`; on success stores the result in
// *out. Errors name the parameter and the value. Giving kd (or hc_damping)
// without restitution switches restitution to "off"; when both are given,
// restitution decides (so that Params() fed back gives the same method).
Status ParsePenaltyParams(const char* method, const ParamMap& params, const PenaltyParams& current,
                          PenaltyParams* out);

ParamMap PenaltyParamsToMap(const PenaltyParams& p);

}  // namespace contactsim
