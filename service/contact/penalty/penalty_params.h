// Parameters of the penalty method (penalty_method.h): the struct holds the
// defaults; each one's range, unit and meaning are declared once, in
// PenaltyParamTable() (penalty_params.cpp; param_table.h).
// ParsePenaltyParams validates a whole ParamMap before changing anything,
// so a bad value leaves the old parameters in place.
#pragma once

#include <string>

#include "service/contact/joint_substeps.h"
#include "service/contact/param_table.h"

namespace contactsim {

struct PenaltyParams {
  std::string model = "linear";
  double kp = 1.0e6;                    // N/m (N/m^n for hunt_crossley), used when contact_time = 0
  // s: half period of a contact's spring against the heaviest body of its
  // island (penalty_stiffness.h); 0 = the fixed kp
  double contact_time = 0.004;
  double kd = 1.0e3;                    // N s/m
  std::string restitution = "material";
  // explicit: "sequential" resolves a pair that meets faster than
  // impact_threshold by the sequential-impacts stage before its springs act
  // (penalty_impacts.h); "springs" leaves every impact to the springs
  std::string impacts = "sequential";
  double impact_threshold = 0.01;       // m/s, raised to 2 |g| dt under gravity
  double hc_exponent = 1.5;
  double hc_damping = 0.2;              // s/m
  double friction_stiffness = 1.0e6;    // N/m
  double friction_damping_ratio = 1.0;
  std::string integrator = "explicit";
  double theta = 1.0;
  int substeps = 1;
  double max_omega_h = 0.15;            // explicit: a rebounding pair's sqrt(kp / m_eff) h per sub-step at most
  int iterations = 20;
  double margin = 0.005;                // m
  // m/s: the speed at which an overlap a pair already had when it was first
  // seen (placement, a pose set, a switch from another method) is pushed
  // out; the spring takes the overlap as its rest depth (penalty_row.h)
  double overlap_push_speed = 0.005;
  // explicit: "placed" (the default) starts the springs of a component
  // placed at rest compressed by their share of its static load
  // (penalty_preload.h); "off" starts them at their rest length
  // (docs/methods/penalty.md, "Load-aware start")
  std::string preload = "placed";
  // m/s: the speed at which such a start's compression (a negative rest
  // depth) is given back, so the springs come to their own equilibrium
  double preload_drain_speed = 0.001;
  double joint_substep_ratio = 100.0;
  int joint_substeps = 4;

  // the restitution as a number, or -1 for "material" / "off"
  double RestitutionValue() const;
};

const ParamTable<PenaltyParams>& PenaltyParamTable();

// Reads `params` over a copy of `current`; on success stores the result in
// *out. Errors name the parameter and the value. Giving kd (or hc_damping)
// without restitution switches restitution to "off", and giving kp (or
// friction_stiffness) without contact_time sets contact_time to 0 (the fixed
// stiffness); when both are given, restitution and contact_time decide (so
// that Params() fed back gives the same method).
Status ParsePenaltyParams(const char* method, const ParamMap& params, const PenaltyParams& current,
                          PenaltyParams* out);

}  // namespace contactsim
