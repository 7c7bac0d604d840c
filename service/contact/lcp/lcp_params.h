// Parameters of the lcp contact method, with units and defaults; read from
// text by ParamReader (errors name the parameter and the value).
#pragma once

#include <string>

#include "service/contact/contact_method.h"

namespace contactsim {

struct LcpParams {
  std::string solver = "pgs";            // pgs | lemke
  int iterations = 20;                   // pgs: sweeps per step at most
  double tolerance = 1e-6;               // m/s: pgs stops when no row velocity changes more in a sweep
  bool warm_start = true;                // pgs: start from last step's impulses (matched by feature id)
  int max_pivots = 0;                    // lemke: pivot cap, 0 = 50 (n + 1) for n LCP variables
  int max_lemke_rows = 600;              // lemke: larger problems are solved by pgs (counted as fallbacks)
  double restitution_threshold = 0.01;   // m/s: approach speed above which Newton restitution applies
  double slop = 1e-3;                    // m: penetration left alone; speculative contact margin
  std::string drift = "split";           // split | baumgarte: how penetration is removed
  double erp = 0.2;                      // 1/step: fraction of (depth - slop) removed per step
  // pgs: components whose heaviest body is this many times their lightest
  // get a direct solve of their normal and joint rows (subspace_solve.h); 0 = off
  double direct_mass_ratio = 10.0;
  int direct_max_rows = 300;             // pgs: larger components keep the sweeps' answer
};

// Validates params against the ranges below and writes *out only when every
// entry is valid (out may alias current).
Status ParseLcpParams(const char* method, const ParamMap& params, const LcpParams& current, LcpParams* out);
ParamMap LcpParamsToMap(const LcpParams& p);

}  // namespace contactsim
