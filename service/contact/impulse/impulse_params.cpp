#include "service/contact/impulse/impulse_params.h"

#include "service/contact/direct_solve_params.h"
#include "service/contact/patch_torsion.h"

namespace contactsim {

const ParamTable<ImpulseParams>& ImpulseParamTable() {
  using P = ImpulseParams;
  static const ParamTable<P> table = {
      IntParam("iterations", &P::iterations, 1, 10000, "", "contact-phase sweeps at most"),
      IntParam("impact_sweeps", &P::impact_sweeps, 0, 10000, "",
               "contact-phase sweeps at most in a sub-step after an impact, before its impact check; found free "
               "of impacts, it is swept again with iterations; 0 = off"),
      IntParam("collision_passes", &P::collision_passes, 1, 10000, "", "collision-phase sweeps at most"),
      DoubleParam("velocity_tolerance", &P::velocity_tolerance, 0.0, 1.0, "m/s",
                  "sweeping stops when no impulse changes a relative velocity more"),
      DoubleParam("collision_threshold", &P::collision_threshold, 0.0, 10.0, "m/s",
                  "approach speed above which restitution applies"),
      DoubleParam("slop", &P::slop, 0.0, 0.1, "m", "penetration left alone; speculative contact margin"),
      DoubleParam("position_correction", &P::position_correction, 0.0, 1.0, "",
                  "fraction of (depth - slop) removed per step by the split impulse"),
      ChoiceParam("toi", &P::toi, {"regula_falsi", "bisection", "off"}, "root finder of the collision time"),
      IntParam("max_substeps", &P::max_substeps, 1, 64, "", "time-of-impact sub-steps per step at most"),
      BoolParam("warm_start", &P::warm_start, "start the contact phase from last step's forces"),
      DirectMassRatioParam(&P::direct_mass_ratio),
      DirectMaxRowsParam(&P::direct_max_rows),
      JointSubstepRatioParam(&P::joint_substep_ratio),
      JointSubstepsParam(&P::joint_substeps),
      PatchTorsionParam(&P::patch_torsion),
  };
  return table;
}

}  // namespace contactsim
