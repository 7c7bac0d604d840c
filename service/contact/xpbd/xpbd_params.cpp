#include "service/contact/xpbd/xpbd_params.h"

#include "service/contact/patch_torsion.h"

namespace contactsim {

const ParamTable<XpbdParams>& XpbdParamTable() {
  using P = XpbdParams;
  static const ParamTable<P> table = {
      IntParam("substeps", &P::substeps, 1, 1000, "",
               "sub-steps per step (more where a heavy body rests on a light one)"),
      IntParam("iterations", &P::iterations, 1, 1000, "", "position iterations per sub-step"),
      DoubleParam("compliance", &P::compliance, 0.0, 1.0, "m/N", "inverse contact stiffness (0: rigid)"),
      DoubleParam("joint_compliance", &P::joint_compliance, 0.0, 1.0, "m/N",
                  "inverse joint stiffness, rad/(N m) for angles (0: rigid)"),
      DoubleParam("restitution_threshold", &P::restitution_threshold, 0.0, 100.0, "m/s",
                  "restitution applies above max(this, 2 |g| h)"),
      DoubleParam("margin", &P::margin, 0.0, 1.0, "m", "detection distance beyond each pair's closing motion"),
      DoubleParam("direct_mass_ratio", &P::direct_mass_ratio, 0.0, 1e12, "",
                  "the contacts of components that join bodies this many times heavier than others are solved "
                  "exactly after each sub-step's sweeps (xpbd_ratio_solve.h); 0 = off"),
      DoubleParam("max_push_velocity", &P::max_push_velocity, 1e-6, 1e3, "m/s",
                  "an overlap is removed at most this fast (h times it per sub-step)"),
      IntParam("velocity_iterations", &P::velocity_iterations, 1, 1000, "",
               "sweeps of the velocity pass per sub-step at most (fewer once a sweep changes no velocity by "
               "more than 1e-5 m/s)"),
      DoubleParam("start_overlap_velocity", &P::start_overlap_velocity, 1e-6, 1e3, "m/s",
                  "an overlap present at a step's start on a pair new to contact is removed at this speed, in "
                  "position only"),
      DoubleParam("start_overlap_time", &P::start_overlap_time, 1e-6, 1e3, "s",
                  "or within this time where that is faster (deep overlaps)"),
      PatchTorsionParam(&P::patch_torsion),
  };
  return table;
}

}  // namespace contactsim
