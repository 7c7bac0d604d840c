// Restitution across simultaneous contacts for the methods that solve their
// contacts without bounce and then drive each point that pushed to a
// velocity target: soft (Box2D v3's restitution pass, Catto, Solver2D
// "Soft Step", 2024) and xpbd (the velocity pass, Mueller et al. 2020,
// "Detailed rigid body simulation with extended position based dynamics",
// eq. 34).
//
// Both papers target v_n+ = -e v_n- with v_n- a point's own approach before
// the solve. That knows one impact per point: in a row of touching bodies
// struck at one end only the first pair approaches before the solve, the
// others meet inside it, are held to 0, and the row leaves together (soft's
// cradle of five under e = 1 kept 36% of its energy; docs/physics.md,
// "Restitution across simultaneous contacts"). Here the targets are
// the outcome of the impacts taken one at a time instead (Guendelman,
// Bridson and Fedkiw 2003, "Nonconvex rigid bodies with stacking", the
// collision phase of the impulse method):
//  1. on a copy of the velocities before the solve, each body pair with a
//     point approaching faster than the threshold collides, its points
//     together (Gauss-Seidel with accumulated j >= 0), to
//       u_n+ >= -e u_n-  where it approached, u_n+ >= 0 elsewhere
//     (Newton's law, Hahn 1988; Mirtich 1996), a row with friction taking
//     Coulomb's impulse within mu j along with its normal (as the impulse
//     method's collisions do), pass after pass until none
//     approaches; this carries a strike down a row as a Newton's cradle
//     does. u_n = v_n + gain, gain <= 0 the approach a pair that met within
//     the step gained over its gap (the method's free-flight impact speed);
//  2. each point's target is the u_n it leaves that phase with;
//  3. on the method's solved velocities, Gauss-Seidel on the rows
//       v_n >= target, accumulated impulse lambda >= 0 (from the method's
//       own accumulated impulse), passes until no impulse changes the
//       velocities by more than 1e-6 of the largest target (a tenth of the
//       threshold where all are about 0), at most 100, a pair's points
//       swept until they agree within each pass; a row with friction
//       holds the slip the method's solve left, within mu times what this
//       solve changed its normal impulse by (the method's friction already
//       spent the cone of the method's own), so that the stage's normal
//       impulses do not undo the method's friction.
// In 1D (a row) the targets fix every relative velocity, so with the
// momentum the rows' answer is the sequential one. The rows are those of the
// contact components (bodies joined by pushing points) that hold a point
// with restitution, with or without an impact this step: in the steps after
// an impact the method's push-out of the overlap it left must not become
// velocity either (a row of six gained 15% of its energy when only
// components with an impact took part). A component without restitution
// takes part where the caller marks a row `struck` (soft and xpbd: a
// point that met faster than the threshold, or that the method's solve
// left parting: its push-out), so that e = 0 gives the one-at-a-time
// answer too (every pair of a struck row leaves at the same speed) where
// the method's own passes stop short of it; a struck row with friction
// does so only in a component that no static or kinematic body holds (a
// row struck in free flight): under gravity the falling piles meet such
// strikes in nearly every step, and the stage over the whole pile tripled
// soft's step and took xpbd's from 17 to 88-102 ms (docs/physics.md,
// "Restitution across simultaneous contacts"). The
// others are left to the method. Every impulse is equal and opposite, so
// momentum is kept.
#pragma once

#include <vector>

#include "service/contact/soft/soft_bodies.h"
#include "service/physics/math.h"

namespace contactsim {

// A friction row of an ImpactRow: unit tangent d perpendicular to n, r x d
// and I^-1 (r x d) of each body.
struct ImpactTangent {
  Vec3 d, ra, rb, ia, ib;
  double lambda = 0.0;  // N s, out: step 3's friction impulse along d
  double held = 0.0;    // m/s, out: the slip along d step 3 holds (the method's)
  double phase = 0.0;   // N s, out: step 1's friction impulse along d, summed over its collisions
};

struct ImpactRow {
  int point = -1;       // the method's point index (for the caller)
  int group = -1;       // rows of one body pair with one normal (a block) share it, consecutively
  int a = -1, b = -1;   // body indices (the world's)
  Vec3 n, ra_n, rb_n;   // unit normal from A to B; r x n of each body
  Vec3 ia_n, ib_n;      // I^-1 (r x n), zero for a body that does not move
  double mass_n = 0.0;  // kg, 1 / K along n
  double restitution = 0.0;
  // with restitution 0, whether the row's component takes part all the same
  // (above; with friction only where no static or kinematic body holds the
  // component); the caller's choice, false where it leaves e = 0 to its solve
  bool struck = false;
  // m/s, the normal velocity at which the pair met: where it is below v_n
  // before the solve (a pair apart that gained approach over its gap in
  // free flight) the difference is the row's gain (step 1); else 0
  double impact = 0.0;
  // Coulomb coefficient: > 0, the row's impacts (step 1) and solve (step
  // 3) take friction along t (above); the caller's choice, 0: normal only
  double friction = 0.0;
  ImpactTangent t[2];
  double lambda = 0.0;  // N s: in, the method's accumulated impulse; out, after step 3
  double target = 0.0;  // m/s, out (step 2)
  double phase = 0.0;   // N s, out: the impulse step 1 gave the row, summed over its collisions
};

// How far step 1 follows a cascade of impacts; the defaults are soft's and
// xpbd's.
struct ImpactCascade {
  // > 0: after the first pass, pairs keep colliding while they approach
  // faster than this share of the phase's fastest approach (if that is
  // below the threshold): with e < 1 a struck row meets again and again,
  // each time e times slower, and pairs stopped at the threshold move on
  // together (0.5 m/s into six touching spheres with e = 0.5 and a
  // 0.01 m/s threshold: 0.017 v0 off the one-at-a-time answer)
  double relative = 0.0;
  int max_passes = 20;
};

class SequentialImpacts {
 public:
  // Starts a new set of rows over `bodies` world bodies.
  void Begin(int bodies);
  // A body's velocities before the solve (once per body, before its rows).
  void SetBody(int index, const Vec3& v, const Vec3& w, double inv_mass);
  bool HasBody(int index) const { return local_[index] >= 0; }
  void AddRow(const ImpactRow& row) { rows_.push_back(row); }
  // Steps 1 and 2 (threshold in m/s); keeps only the rows of components
  // with restitution or a struck row and returns whether any is left.
  bool FindTargets(double threshold, const ImpactCascade& cascade = ImpactCascade());
  // Step 3 on the method's bodies.
  void Solve(std::vector<SoftBody>& bodies);
  const std::vector<ImpactRow>& rows() const { return rows_; }

 private:
  struct Velocity {
    Vec3 v, w;
    double inv_mass;
  };
  // the 2 x 2 inverse mass of a row's friction (slip_friction_step.h)
  struct TangentMass {
    double m1 = 0.0, m2 = 0.0, k12 = 0.0;
  };
  double Approach(int k) const;  // row k's u_n on the copy
  double Slip(int k, int axis) const;  // row k's u along t[axis] on the copy
  void Push(double j, const ImpactRow& r);
  // one update of row k's friction in a collision (within friction j_[k]);
  // returns the velocity change (m/s)
  double CollideFriction(int k);
  void SetTangentMasses();
  // one Gauss-Seidel update of row k on the method's bodies (step 3);
  // returns the velocity change (m/s)
  double SolveRow(int k, std::vector<SoftBody>& bodies);
  // one collision of the rows [begin, end): false when none approached
  bool Collide(int begin, int end, double threshold);
  void KeepTakingPartComponents();
  void SetGains();

  std::vector<int> local_;        // per world body: its index in start_, -1 if none
  std::vector<int> touched_;      // world bodies with local_ set
  std::vector<Velocity> start_;   // velocities before the solve
  std::vector<Velocity> scratch_;  // step 1's copy
  std::vector<ImpactRow> rows_;
  std::vector<double> j_;
  std::vector<double> jt_;            // per row, 2: step 1's friction impulses in a collision
  std::vector<TangentMass> tangent_;  // per row, for rows with friction
  std::vector<double> method_lambda_;  // per row, N s: the rows' lambda on entering Solve
  std::vector<double> gain_;  // per row, m/s, <= 0
  double threshold_ = 0.0;    // m/s, FindTargets'
};

}  // namespace contactsim
