#include "service/contact/penalty_params.h"

#include <cstdlib>

#include "service/contact/param_reader.h"

namespace contactsim {
namespace {

// Stiffness up to 1e15 N/m so that the stable-kp search of the implicit
// integrator is not cut off by the range (BENCHMARKS.md).
constexpr double kMaxStiffness = 1.0e15;  // N/m
constexpr double kMaxDamping = 1.0e9;     // N s/m

bool IsRestitutionWord(const std::string& s) { return s == "material" || s == "off"; }

}  // namespace

double PenaltyParams::RestitutionValue() const {
  return IsRestitutionWord(restitution) ? -1.0 : std::strtod(restitution.c_str(), nullptr);
}

Status ParsePenaltyParams(const char* method, const ParamMap& params, const PenaltyParams& current,
                          PenaltyParams* out) {
  PenaltyParams p = current;
  ParamReader r(method, params);
  r.Choice("model", {"linear", "hunt_crossley"}, &p.model);
  r.Double("kp", 1.0, kMaxStiffness, &p.kp);
  r.Double("kd", 0.0, kMaxDamping, &p.kd);
  r.Double("hc_exponent", 1.0, 3.0, &p.hc_exponent);
  r.Double("hc_damping", 0.0, 100.0, &p.hc_damping);
  r.Double("friction_stiffness", 1.0, kMaxStiffness, &p.friction_stiffness);
  r.Double("friction_damping_ratio", 0.0, 100.0, &p.friction_damping_ratio);
  r.Choice("integrator", {"explicit", "implicit"}, &p.integrator);
  r.Double("theta", 0.5, 1.0, &p.theta);
  r.Int("substeps", 1, 1000, &p.substeps);
  r.Int("iterations", 1, 1000, &p.iterations);
  r.Double("margin", 0.0, 0.1, &p.margin);

  // restitution is a word or a number in [0, 1]
  const auto e = params.find("restitution");
  if (e != params.end() && !IsRestitutionWord(e->second)) {
    char* end = nullptr;
    std::strtod(e->second.c_str(), &end);
    if (e->second.empty() || *end != '\0') {
      return Status::InvalidArgument(std::string(method) +
                                     " parameter restitution must be material, off or a number in [0, 1], got \"" +
                                     e->second + "\"");
    }
  }
  if (e != params.end() && IsRestitutionWord(e->second)) {
    r.Choice("restitution", {"material", "off"}, &p.restitution);
  } else {
    double value = -1.0;
    r.Double("restitution", 0.0, 1.0, &value);
    if (value >= 0.0) p.restitution = FormatValue(value);
  }
  Status status = r.Finish();
  if (!status.ok()) return status;

  // kd alone means "use kd"; with restitution also given (as Params()
  // lists them) restitution decides, so Params() round-trips
  const bool gives_damping = params.count("kd") > 0 || params.count("hc_damping") > 0;
  if (gives_damping && e == params.end()) p.restitution = "off";
  *out = p;
  return Status::Ok();
}

ParamMap PenaltyParamsToMap(const PenaltyParams& p) {
  return {{"model", p.model},
          {"kp", FormatValue(p.kp)},
          {"kd", FormatValue(p.kd)},
          {"restitution", p.restitution},
          {"hc_exponent", FormatValue(p.hc_exponent)},
          {"hc_damping", FormatValue(p.hc_damping)},
          {"friction_stiffness", FormatValue(p.friction_stiffness)},
          {"friction_damping_ratio", FormatValue(p.friction_damping_ratio)},
          {"integrator", p.integrator},
          {"theta", FormatValue(p.theta)},
          {"substeps", std::to_string(p.substeps)},
          {"iterations", std::to_string(p.iterations)},
          {"margin", FormatValue(p.margin)}};
}

}  // namespace contactsim
