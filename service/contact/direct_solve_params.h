// The two parameters of the methods that solve mass-ratio components
// directly after their sweeps (subspace_solve.h), declared once.
// `pgs_only`: the method has other solvers that do not use them (lcp).
#pragma once

#include "service/contact/param_table.h"

namespace contactsim {

template <class P>
ParamField<P> DirectMassRatioParam(double P::*member, bool pgs_only = false) {
  return DoubleParam("direct_mass_ratio", member, 0.0, 1e12, "",
                     pgs_only ? "pgs: components whose heaviest body is this many times their lightest get a "
                                "direct solve of their rows after the sweeps (subspace_solve.h); 0 = off"
                              : "components whose heaviest body is this many times their lightest get a direct "
                                "solve of their rows after the sweeps (subspace_solve.h); 0 = off");
}
template <class P>
ParamField<P> DirectMaxRowsParam(int P::*member, bool pgs_only = false) {
  return IntParam("direct_max_rows", member, 0, 10000, "",
                  pgs_only ? "pgs: larger components keep the sweeps' answer" : "larger components keep the sweeps' answer");
}

}  // namespace contactsim
