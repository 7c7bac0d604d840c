// The penalty method's load-aware start (`preload` = on): a contact
// component placed at rest starts with its springs carrying the static
// load, instead of unloaded.
//
// Why: a spring that starts at its rest length carries nothing, so bodies
// placed touching fall into their springs until these carry their weight,
// and ring there: g contact_time / pi = 1.25 cm/s a course of load at a
// 4 ms contact time, 2.2 cm/s at the top of a stack of three cubes
// (docs/methods/penalty.md, "Load-aware start"). A spring compressed by
// its share of the load at the placement holds the bodies where they were
// placed.
//
//  1. the component: dynamic bodies joined by rows touching now (spring
//     depth d - d_rest above -kTouching); it is placed at rest when none
//     of its touching rows was seen in the step before (no anchor: a
//     placement, a pose set, a switch from another method) and none
//     approaches or parts faster than the impact threshold;
//  2. its rigid static loads: the normal forces lambda >= 0 that keep every
//     touching row from approaching under the bodies' external wrenches
//     (Gauss-Seidel on the rows' accelerations, the projected iteration of
//     the velocity solvers with a step of 1 s: Catto 2005, "Iterative
//     dynamics with temporal coherence"), until no force changes a row's
//     acceleration by more than 1e-6 of the largest one, at most 500
//     passes;
//  3. each row's spring starts compressed by its load: its rest depth
//     becomes d - lambda nc / kp (linear; (lambda nc / kp)^(1 / n) for
//     Hunt-Crossley), negative where the row only touches. The rest depth
//     is kept while the contact lasts (`preload_drain_speed` = 0, the
//     default), so the bodies stay where they were placed; a positive
//     speed gives it back, and the springs sink to their own equilibrium
//     depth (a stack of n courses at n times that speed at its top).
#pragma once

#include <vector>

#include "service/contact/penalty/penalty_params.h"
#include "service/contact/penalty/penalty_row.h"
#include "service/physics/world.h"

namespace contactsim {

class PenaltyPreload {
 public:
  // Steps 1-3 on the step's rows (after BuildPenaltyRows, with the world's
  // forces accumulated); `threshold` in m/s. Returns the rows preloaded.
  int Apply(const World& world, const PenaltyParams& params, double threshold, std::vector<PenaltyRow>* rows);

 private:
  struct Row {
    int row;             // index into the step's rows
    int a, b;            // body indices
    Vec3 n, ra_n, rb_n;  // unit normal; r x n of each body
    Vec3 ia_n, ib_n;     // I^-1 (r x n), zero for a body that does not move
    double mass_n;       // kg, 1 / K along n
    double lambda;       // N, the row's static load
  };
  // step 2 over rows_; accelerations in acc_v_ / acc_w_
  void SolveLoads();
  // step 2's loads of each pair's points made linear over the points
  // (those of equal springs under a rigid pair), keeping the pair's force
  // and moment
  void SpreadOverPairs(const std::vector<PenaltyRow>& rows);
  double Approach(const Row& r) const;

  std::vector<Row> rows_;
  std::vector<Vec3> acc_v_, acc_w_;  // per body, m/s^2 and rad/s^2
  std::vector<double> inv_mass_;     // per body, 0 for a body that does not move
  std::vector<int> first_, next_;    // per pair its first entry of rows_, per entry the pair's next
};

}  // namespace contactsim
