// The penalty method's impact stage (`impacts` = sequential): at the
// sub-step where a point's spring first bites into a pair approaching
// faster than the threshold, the impacts of its contact component are
// taken one at a time by the shared sequential-impacts stage
// (sequential_impacts.h, steps 1-2: Guendelman, Bridson and Fedkiw 2003,
// Newton's law v_n+ = -e v_n- on each pair that meets, pass after pass),
// and the impulses of that phase are applied to the bodies before the
// springs and dashpots act. The springs then carry only resting load.
//
// Why: a row of touching bodies struck at one end is a chain of equal
// springs, which spreads the strike over the row whatever the stiffness
// (the chain has no time scale but its own: every contact time gives the
// same outcome at gap 0), so no spring law leaves the row with the
// velocities of one impact at a time (docs/methods/penalty.md,
// "Restitution across simultaneous contacts").
//
//  1. struck rows: approaching faster than the threshold and closing
//     within the sub-step at that speed (spring depth d - d_rest - vn h > 0
//     and d - d_rest <= -vn h: the impact is taken as the spring would
//     first bite, not one sub-step into it, whose overlap the spring would
//     push out again; a loaded spring ringing faster than the threshold is
//     no impact: taking it as one set its rest depth deeper at each ring,
//     and a Hunt-Crossley box sank 0.13 m),
//     with a known restitution e >= 0 (not restitution = off); a row with
//     friction and e = 0 only in a component that no static or kinematic
//     body holds (a strike in free flight, as soft's and xpbd's: a landing
//     keeps its springs, dashpots and friction, and a pile under gravity
//     meets such strikes in nearly every sub-step);
//  2. the rows that take part: those of the components (dynamic bodies
//     joined by rows) that hold a struck row, touching or apart by less
//     than the fastest strike closes in two sub-steps, 2 v h (the gaps of
//     a row of nearly touching bodies close within the strike: 0.1 mm at
//     0.5 m/s in 0.2 ms, a sub-step of a 4 ms contact time; a wider gap is
//     left to the sub-steps, whose stage takes it when it closes); a row
//     with friction and e = 0 takes Coulomb's impulse within each of its
//     collisions (sequential_impacts.h, step 1), a rebounding one none;
//  3. the impacts on the bodies' velocities now (ImpactCascade: until the
//     pairs approach slower than 1e-3 of the strike, at most 100 passes, as
//     lcp's), and each row's phase impulse, normal and friction, applied
//     to its bodies (the normal one added to the row's `impulse`, which
//     the step reports);
//  4. a row that took an impulse while already compressed starts its
//     spring at the depth it has now (its rest depth, penalty_row.h, which
//     then drains at overlap_push_speed): the stage's impulse replaces the
//     spring's rebound, so the spring must not push the impact's overlap
//     out again (at a 4 ms contact time and 22 sub-steps the overlap of one
//     sub-step would part an e = 0 pair at up to 0.15 v0).
// Every impulse is equal and opposite, so momentum is kept.
#pragma once

#include <vector>

#include "service/contact/penalty/penalty_row.h"
#include "service/contact/sequential_impacts.h"
#include "service/physics/world.h"

namespace contactsim {

// A row's state at the sub-step: its lever arms, normal velocity and
// spring's depth now.
struct ImpactArms {
  Vec3 ra, rb;                // m, world
  double vn = 0.0;            // m/s, n . (v_B - v_A) at the arms, < 0 approaching
  double spring_depth = 0.0;  // m, d - d_rest (> 0 compressed)
};

// Whether the row's law lets it be struck (step 1 without its speed and
// its component): engaged, with a known restitution.
inline bool MayBeStruck(const PenaltyRow& row) { return row.engaged && row.restitution >= 0.0; }

// Whether a step over `rows` may hold an impact for the stage: a row that
// may be struck with restitution > 0 or without friction, or one with
// friction and e = 0 in a component of the step's engaged rows that no
// static or kinematic body holds (each sub-step's components lie within
// those). A pile at rest under gravity with friction and e = 0 runs none of
// the stage (its look at every row each sub-step cost the pyramid 6.7% of
// its instructions).
bool MayHoldImpact(const World& world, const std::vector<PenaltyRow>& rows);

class PenaltyImpacts {
 public:
  // Steps 1-4 on the world's bodies; `threshold` in m/s, `h` the sub-step
  // and `dt` the world step (s). Returns whether any impulse was applied.
  bool Resolve(World& world, std::vector<PenaltyRow>& rows, const std::vector<ImpactArms>& arms, double threshold,
               double h, double dt);

 private:
  SequentialImpacts impacts_;
  std::vector<int> root_;      // per body: its component's root, -1 static
  std::vector<char> held_;     // per root: a static or kinematic body touches the component
  std::vector<char> struck_;   // per root: holds a struck row
};

// The stage's threshold: the parameter, raised to 2 |g| dt under gravity as
// soft's restitution_threshold, so that a resting contact's approach (at
// most |g| dt a step) is never an impact.
double PenaltyImpactThreshold(const World& world, double impact_threshold);

}  // namespace contactsim
