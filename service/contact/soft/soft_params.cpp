#include "service/contact/soft/soft_params.h"

#include "service/contact/direct_solve_params.h"
#include "service/contact/patch_torsion.h"

namespace contactsim {

const ParamTable<SoftParams>& SoftParamTable() {
  using P = SoftParams;
  static const ParamTable<P> table = {
      IntParam("substeps", &P::substeps, 1, 64, "", "sub-steps per step, each with one solve and relax pass"),
      IntParam("relax_iterations", &P::relax_iterations, 0, 64, "",
               "passes without the soft push-out after each sub-step's positions move"),
      IntParam("joint_passes", &P::joint_passes, 1, 64, "",
               "in a world with joints, contact passes and exact joint solves taken in turn in each solve and "
               "relax stage (soft_joints.h): one leaves the joints' last correction unseen by friction"),
      DoubleParam("contact_hertz", &P::contact_hertz, 0.1, 1e4, "Hz",
                  "contact spring frequency, capped at a quarter of the sub-step rate (twice it against static "
                  "bodies)"),
      DoubleParam("damping_ratio", &P::damping_ratio, 0.0, 1e3, "", "contact spring damping ratio"),
      DoubleParam("max_push_velocity", &P::max_push_velocity, 0.0, 100.0, "m/s",
                  "fastest the soft spring pushes overlapping bodies apart"),
      DoubleParam("restitution_threshold", &P::restitution_threshold, 0.0, 100.0, "m/s",
                  "restitution applies to points approaching faster than max(this, 2 |g| dt), the floor keeping a "
                  "resting contact from bouncing"),
      DoubleParam("margin", &P::margin, 0.0, 1.0, "m", "speculative distance beyond each pair's closing motion"),
      BoolParam("warm_start", &P::warm_start, "start each step from the last step's impulses"),
      DirectMassRatioParam(&P::direct_mass_ratio),
      DirectMaxRowsParam(&P::direct_max_rows),
      PatchTorsionParam(&P::patch_torsion),
      ChoiceParam("precision", &P::precision, {"double", "float"},
                  "the sub-steps' contact passes in double, one point at a time, or in single precision over SIMD "
                  "lanes, a manifold a lane (wide/soft_wide_solver.h); worlds with joints or a heavy-on-light "
                  "component keep double"),
      ChoiceParam("float_lanes", &P::float_lanes, {"widest", "4", "8"},
                  "manifolds a SIMD bundle holds under precision=float: the widest the processor runs, or 4 "
                  "(SSE2) or 8 (AVX, where the processor has it); the result is the same at either width"),
  };
  return table;
}

}  // namespace contactsim
