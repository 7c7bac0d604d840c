#include "service/contact/penalty/penalty_params.h"

#include <cstdlib>

namespace contactsim {
namespace {

// Stiffness up to 1e15 N/m so that the stable-kp search of the implicit
// integrator is not cut off by the range (BENCHMARKS.md, "Penalty: largest
// stable kp").
constexpr double kMaxStiffness = 1.0e15;  // N/m
constexpr double kMaxDamping = 1.0e9;     // N s/m

}  // namespace

double PenaltyParams::RestitutionValue() const {
  return restitution == "material" || restitution == "off" ? -1.0 : std::strtod(restitution.c_str(), nullptr);
}

const ParamTable<PenaltyParams>& PenaltyParamTable() {
  using P = PenaltyParams;
  static const ParamTable<P> table = {
      DoubleParam("kp", &P::kp, 1.0, kMaxStiffness, "N/m",
                  "pair stiffness (N/m^n for hunt_crossley) when contact_time = 0 (giving kp alone sets 0)"),
      DoubleParam("contact_time", &P::contact_time, 0.0, 1.0, "s",
                  "linear law: a pair's stiffness gives its spring this half period against the heaviest body of "
                  "its island, m pi^2 / contact_time^2 (penalty_stiffness.h); 0 = the fixed kp and friction_stiffness"),
      DoubleParam("kd", &P::kd, 0.0, kMaxDamping, "N s/m",
                  "pair damping, used when restitution = off (giving kd alone sets off)"),
      ChoiceOrNumberParam("restitution", &P::restitution, {"material", "off"}, 0.0, 1.0,
                          "damping source: material derives kd (or the Hunt-Crossley alpha) from the pair's "
                          "max(e_a, e_b), a number from that value, off uses kd / hc_damping"),
      ChoiceParam("impacts", &P::impacts, {"sequential", "springs"},
                  "explicit: sequential resolves the impacts of a component whose pair meets faster than "
                  "impact_threshold one at a time before its springs act (penalty_impacts.h); springs leaves them "
                  "to the springs and dashpots"),
      DoubleParam("impact_threshold", &P::impact_threshold, 0.0, 100.0, "m/s",
                  "explicit, impacts = sequential: a touching pair approaching faster than max(this, 2 |g| dt) "
                  "is an impact"),
      ChoiceParam("model", &P::model, {"linear", "hunt_crossley"}, "normal force law"),
      DoubleParam("hc_exponent", &P::hc_exponent, 1.0, 3.0, "", "n of kp d^n (1.5: Hertz contact of spheres)"),
      DoubleParam("hc_damping", &P::hc_damping, 0.0, 100.0, "s/m", "Hunt-Crossley alpha when restitution = off"),
      ChoiceParam("integrator", &P::integrator, {"explicit", "implicit"},
                  "explicit sub-steps (penalty_explicit.h), or linearly implicit (penalty_implicit.h)"),
      DoubleParam("theta", &P::theta, 0.5, 1.0, "", "implicit: 1 = linearly implicit Euler, 0.5 = trapezoidal"),
      IntParam("substeps", &P::substeps, 1, 1000, "",
               "steps of dt / substeps per world step (explicit: at least; more are added for max_omega_h)"),
      DoubleParam("max_omega_h", &P::max_omega_h, 0.01, 2.0, "",
                  "explicit: sub-steps are added until every rebounding pair's spring has sqrt(kp / m_eff) h below "
                  "this (restitution 0: sqrt(kp / m_s) h below 1.5 times this) and the stiffest mode omega h "
                  "below 1, up to 1000 (penalty_explicit.h)"),
      IntParam("iterations", &P::iterations, 1, 1000, "", "implicit: active-set passes at most"),
      DoubleParam("friction_stiffness", &P::friction_stiffness, 1.0, kMaxStiffness, "N/m",
                  "tangential spring kt of a pair when contact_time = 0 (else kt = the normal stiffness)"),
      DoubleParam("friction_damping_ratio", &P::friction_damping_ratio, 0.0, 100.0, "",
                  "zeta_t of the tangential spring, 1 = critical"),
      DoubleParam("overlap_push_speed", &P::overlap_push_speed, 1e-6, 1e3, "m/s",
                  "an overlap a pair already had when first seen (deeper than its approach could reach in the "
                  "step) is the spring's rest depth, which shrinks at this speed (penalty_row.h)"),
      ChoiceParam("preload", &P::preload, {"placed", "off"},
                  "explicit: placed starts the springs of a contact component placed at rest (no touching point "
                  "seen before, none moving faster than the impact threshold) compressed by their share of its "
                  "static load (penalty_preload.h); off starts them unloaded"),
      DoubleParam("preload_drain_speed", &P::preload_drain_speed, 0.0, 1e3, "m/s",
                  "the compression a placed start gave a spring (a negative rest depth) is given back at this "
                  "speed, 0 = kept while the contact lasts (penalty_row.h)"),
      DoubleParam("margin", &P::margin, 0.0, 0.1, "m", "contacts up to this gap are detected (implicit: predicted; explicit: plus what the step can close)"),
      JointSubstepRatioParam(&P::joint_substep_ratio),
      JointSubstepsParam(&P::joint_substeps),
  };
  return table;
}

Status ParsePenaltyParams(const char* method, const ParamMap& params, const PenaltyParams& current,
                          PenaltyParams* out) {
  PenaltyParams p;
  const Status status = PenaltyParamTable().Parse(method, params, current, &p);
  if (!status.ok()) return status;
  // kd alone means "use kd"; with restitution also given (as Params()
  // lists them) restitution decides, so Params() round-trips
  const bool gives_damping = params.count("kd") > 0 || params.count("hc_damping") > 0;
  if (gives_damping && params.count("restitution") == 0) p.restitution = "off";
  // likewise kp alone means "use kp"
  const bool gives_stiffness = params.count("kp") > 0 || params.count("friction_stiffness") > 0;
  if (gives_stiffness && params.count("contact_time") == 0) p.contact_time = 0.0;
  *out = p;
  return Status::Ok();
}

}  // namespace contactsim
