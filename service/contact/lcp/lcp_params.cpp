#include "service/contact/lcp/lcp_params.h"

#include "service/contact/param_reader.h"

namespace contactsim {

Status ParseLcpParams(const char* method, const ParamMap& params, const LcpParams& current, LcpParams* out) {
  LcpParams p = current;
  ParamReader r(method, params);
  r.Choice("solver", {"pgs", "lemke"}, &p.solver);
  r.Int("iterations", 1, 100000, &p.iterations);
  r.Double("tolerance", 0.0, 1.0, &p.tolerance);
  r.Bool("warm_start", &p.warm_start);
  r.Int("max_pivots", 0, 10000000, &p.max_pivots);
  r.Int("max_lemke_rows", 0, 10000, &p.max_lemke_rows);
  r.Double("restitution_threshold", 0.0, 10.0, &p.restitution_threshold);
  r.Double("slop", 0.0, 0.1, &p.slop);
  r.Choice("drift", {"split", "baumgarte"}, &p.drift);
  r.Double("erp", 0.0, 1.0, &p.erp);
  r.Double("direct_mass_ratio", 0.0, 1e12, &p.direct_mass_ratio);
  r.Int("direct_max_rows", 0, 10000, &p.direct_max_rows);
  Status status = r.Finish();
  if (status.ok()) *out = p;
  return status;
}

ParamMap LcpParamsToMap(const LcpParams& p) {
  return {{"solver", p.solver},
          {"iterations", std::to_string(p.iterations)},
          {"tolerance", FormatValue(p.tolerance)},
          {"warm_start", p.warm_start ? "true" : "false"},
          {"max_pivots", std::to_string(p.max_pivots)},
          {"max_lemke_rows", std::to_string(p.max_lemke_rows)},
          {"restitution_threshold", FormatValue(p.restitution_threshold)},
          {"slop", FormatValue(p.slop)},
          {"drift", p.drift},
          {"erp", FormatValue(p.erp)},
          {"direct_mass_ratio", FormatValue(p.direct_mass_ratio)},
          {"direct_max_rows", std::to_string(p.direct_max_rows)}};
}

}  // namespace contactsim
