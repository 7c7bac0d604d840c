#include "service/contact/lcp/lcp_params.h"

#include "service/contact/direct_solve_params.h"
#include "service/contact/patch_torsion.h"

namespace contactsim {

const ParamTable<LcpParams>& LcpParamTable() {
  using P = LcpParams;
  static const ParamTable<P> table = {
      ChoiceParam("solver", &P::solver, {"pgs", "lemke"}, "projected Gauss-Seidel or Lemke's pivoting method"),
      IntParam("iterations", &P::iterations, 1, 100000, "", "pgs: sweeps per step at most"),
      DoubleParam("tolerance", &P::tolerance, 0.0, 1.0, "m/s",
                  "pgs stops when no row velocity changes more in a sweep (lemke's fallback: at most 1e-6)"),
      BoolParam("warm_start", &P::warm_start,
                "pgs: start from last step's impulses (matched by feature id, else by place)"),
      DoubleParam("restitution_threshold", &P::restitution_threshold, 0.0, 10.0, "m/s",
                  "approach speed above which Newton restitution applies"),
      DoubleParam("slop", &P::slop, 0.0, 0.1, "m", "penetration left alone; speculative contact margin"),
      ChoiceParam("drift", &P::drift, {"split", "baumgarte"}, "how penetration is removed"),
      DoubleParam("erp", &P::erp, 0.0, 1.0, "", "fraction of (depth - slop) removed per step"),
      IntParam("max_pivots", &P::max_pivots, 0, 10000000, "",
               "lemke: pivot cap, 0 = 50 (n + 1) for n LCP variables"),
      IntParam("max_lemke_rows", &P::max_lemke_rows, 0, 10000, "",
               "lemke: larger problems are solved by pgs (counted as fallbacks)"),
      DirectMassRatioParam(&P::direct_mass_ratio, true),
      DirectMaxRowsParam(&P::direct_max_rows, true),
      JointSubstepRatioParam(&P::joint_substep_ratio),
      JointSubstepsParam(&P::joint_substeps),
      PatchTorsionParam(&P::patch_torsion),
      ChoiceParam("impacts", &P::impacts, {"sequential", "simultaneous"},
                  "restitution across contacts that meet in one step: sequential = the impacts one pair at a time "
                  "(Newton's cradle passes its strike on; lcp_impacts.h), simultaneous = one LCP with "
                  "v_n+ >= -e v_n- per contact"),
  };
  return table;
}

}  // namespace contactsim
