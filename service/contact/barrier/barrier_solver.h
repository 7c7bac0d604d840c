// One step of the barrier method: Newton's method on the incremental
// potential of affine bodies with IPC contact (Lan et al. 2022, Affine Body
// Dynamics; Li et al. 2020, Incremental Potential Contact):
//   E(q) = 1/2 (q - q_pred)^T M (q - q_pred)
//          + h^2 (sum V_ortho + kappa sum_k b(d_k) + sum_k mu lambda_k f0(|u_k|)),
//   q_pred = (p_n + h v_n + h^2 F / m, R_pred)   (affine_prediction.h),
// R_pred the rigid rotation advanced by the midpoint rule with L + h tau
// held fixed, not implicit Euler's A_n + h Adot_n (a stretched rotation
// whose pull back to the manifold damped rotation),
// with b the log barrier on each primitive pair's distance (barrier_potential.h,
// contact_primitives.h; edge-edge pairs times IPC's mollifier,
// edge_mollifier.h) and lagged friction (IPC sec. 5): lambda_k =
// kappa m |b'(d_k)| (N, the force of that pair's barrier term), the
// touching points X_a, X_b (body frames; the closest points, moved by the
// radius onto a sphere's or capsule's surface) and the
// tangent basis T_k of the pair at the end of the previous step
// (barrier_state.h), and u_k = T_k^T (x_b(X_b) - x_a(X_a)) the tangential
// motion of those body points over this step, so the friction force
// -mu lambda f1(|u|) T u/|u| acts at the contact point with the affine
// (rigid plus stretch) motion there. q_n and qdot_n are the affine state the
// last step left (barrier_state.h), not re-derived from the rigid pose.
//
// Newton starts from q_n with each body turning fast enough (below)
// moved to its q_pred by the line search below (StartTurningBodiesAtPrediction).
// Each Newton iteration solves H dq = -g with H the sum of M, the projected
// Hessian of the orthogonality potential, the Gauss-Newton barrier term
// kappa b''(d) grad d grad d^T (positive semi-definite; the curvature term
// b'(d) grad^2 d is dropped) and the friction term G H_f G^T with H_f the
// PSD Hessian of mu lambda f0(|u|) in u (IPC appendix), assembled in dense
// 12x12 blocks and solved per connected component (newton_system.h: a lone
// body's 12x12 LDL^T, a sparse LDL^T per contact component).
// The Newton iterations run island by island (barrier_newton.cpp): bodies
// that no pair of the step's line, no pair within d_hat and no friction
// pair joins are separable, so each island has its own line search and
// convergence test, and a converged island leaves the solve until a
// neighbour moves or kappa changes.
// An island's line search starts at the largest alpha in [0, 1] for which
// no pair's distance can fall below ccd_fraction of its current value, by
// additive CCD per pair (additive_ccd.h: conservative advancement with the
// pair's own relative vertex motion, re-measured along the step, so pairs
// sliding past each other do not cut alpha to d / |motion|). It then halves
// alpha until the island's E decreases. Every accepted iterate is therefore
// intersection-free.
// The pairs are found by a broadphase over swept boxes (pair_search.h): one
// search along each Newton step gives every pair that can come within d_hat
// on it with each side anywhere on its own step (the islands take different
// alphas), which serves the CCD, the line searches' energies and,
// re-measured at the accepted iterate, the next iteration's gradient and
// Hessian.
//
// Barrier stiffness (IPC sec. 4.3, adaptive): at the step's start kappa
// balances the barrier's gradient against the rest,
// kappa = -(g_B . g_E) / |g_B|^2, clamped to [kappa_min, 1e6 kappa_min] with
// kappa_min = m_avg max(|g|, 1 m/s^2) / (4 |b'(d_hat / 2)|) (four pairs at
// d_hat / 2, a box face on its corners, hold the average body's weight; a
// larger floor would launch such a box by a multiple of its weight in its
// first step); during the iterations it doubles while the smallest distance
// is below 1e-2 d_hat and still shrinking (the islands with a barrier pair
// are then solved again).
//
// Line-search bound for a point against a static plane: d is linear in
// alpha, d(alpha) = d + alpha n . dx, so the bound is exact and uses only the
// approach along n (a box sliding at 3 m/s, 12 mm a step, 0.5 mm above the
// ground, would otherwise take small fractions of each Newton step).
//
// Pairs that start a step closer than floor = 1e-2 d_hat (pressed
// together) are measured from a shifted zero, d' = d + floor, so the
// barrier pushes them apart instead of being infinite. The zero is the same
// -floor in every step, so a pair pressed below d = 0 gets no lower zero in
// the next step (a zero at d_0 - floor, re-taken every step, let the pyramid
// sink 0.69 mm in 120 steps); near d = 0 point-triangle and crossing
// edge-edge distances are signed (contact_primitives.h), so d' > 0 means
// d > -floor. Pairs that start deeper than -floor get d' = floor at their
// start.
//
// Bodies placed touching. IPC needs an intersection-free start with
// positive distances (Li et al. 2020, sec. 3). Bodies placed exactly
// touching or overlapping by round-off (a wall laid course on course, a
// stack, a pile; or a world switched from a method that rests bodies
// touching or slightly inside each other) would start at the shifted zero
// above, where kappa |b'(floor)| is ~100 times a pair's share of the weight
// at d_hat / 2: each pair was pushed out to the barrier's rest gap and
// beyond (a placed wall rose 1.5 mm and threw the half brick at the end of
// its top course 87 mm). The same holds for a pair placed with a gap inside
// the barrier's resting range: a cube let fall 0.1 mm (0.1 d_hat) onto a
// 40 degree slope was thrown off at 0.06 m/s and slid 5.6 mm before it
// held. A primitive pair closer than kPlacedReach d_hat (where a resting
// pair rests, about d_hat / 2), or overlapping
// (seen as deep as kPlacedDepth d_hat), when one of its bodies starts (its
// first step under this method, after a switch or after a command changed
// it: barrier_state.h) is therefore a placed pair, whose barrier is
//   kappa (d_hat / w) b(d - z; w),  z = d_0 - w,  w = kPlacedWidth d_hat:
// C-IPC's offset barrier (Li, Kaufman and Jiang 2021, sec. 3: the barrier
// on d - xi) with the offset taken per pair so that the distance it was
// placed at, d_0, is the barrier's activation distance, and the barrier
// scaled to w with its forces kept (kappa (d_hat / w) b'(x w; w) =
// kappa b'(x d_hat; d_hat)). A placed pair so starts with zero force and
// zero energy (nothing is pushed: a capsule placed against a box's side
// stays, where a start inside the barrier set it rolling), and under load
// it gives way by at most w, resting where a resting gap would rest in
// d_hat, about halfway (a 0.1 m cube on the ground sinks 0.5 w). So a
// stack of n placed courses sinks by less than n w in its first step and
// stands. Kept at the barrier's own kappa, such a pair rested at 1% of w,
// 10^4 times stiffer than a resting gap, and a cube launched from it at
// 3 m/s tipped over on the lagged friction of its rocking (IPC sec. 5);
// at the scaled kappa it is d_hat / w = 50 times stiffer, and such a cube
// stops within 2% of v0^2 / (2 mu g) (10 kg with mu 0.8 along a face: 6%,
// tests/contact/scenario_tolerances.h). A placed pair keeps its zero and
// width (barrier_state.h) while it is within d_hat at the end of each
// step, and becomes an ordinary pair only beyond, where both barriers are
// zero, so the change adds no energy; its zero never moves down while
// kept (a restarted body's kept pair keeps its zero while it is above it),
// so a placed pair never gets more than w deeper than it was placed; its
// CCD keeps only d - z above ccd_fraction of its value (additive_ccd.h).
// Placed pairs do not grow kappa: under load they rest inside their width
// by design. An unsigned distance of polyhedra that can turn signed (within
// the signed depth, or anywhere between two bodies that start overlapping
// by more than floor) measures no separation: such a pair's zero is taken
// as if the same distance lay behind the face, z = -d_0 - w, so it pushes
// nothing until it turns signed and deeper (with z = d_0 - w, such pairs
// pushed the wrong way, or turned signed below their zero and stopped
// every line search). Pairs that come within floor later keep the shifted
// zero above. Unsigned distances cannot see an overlap deeper than the
// signed depths, so the guarantee assumes a start overlapping by less than
// kPlacedDepth d_hat (planes and spheres have signed distances and recover).
#pragma once

#include <algorithm>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/barrier/additive_ccd.h"
#include "service/contact/barrier/affine_body.h"
#include "service/contact/barrier/barrier_params.h"
#include "service/contact/barrier/barrier_state.h"
#include "service/contact/barrier/contact_primitives.h"
#include "service/contact/barrier/edge_mollifier.h"
#include "service/contact/barrier/newton_system.h"
#include "service/contact/barrier/pair_search.h"
#include "service/physics/world.h"

namespace contactsim {

struct BarrierStepResult {
  int iterations = 0;
  double min_distance = 0.0;    // m, over the pairs within d_hat at the end (d_hat if none)
  double kappa = 0.0;           // N/m, barrier stiffness at the end of the step
  bool converged = false;
};

class BarrierSolver {
 public:
  // Advances the world by world.dt with world.AccumulateForces() already
  // called; fills `contacts` with the pairs within d_hat (forces on B).
  BarrierStepResult Step(World& world, const BarrierParams& params, ContactSet* contacts);
  // The affine state and lagged friction carried between steps
  // (barrier_state.h).
  const BarrierState& state() const { return state_; }
  BarrierState& mutable_state() { return state_; }

 private:
  struct Body {
    int index = -1;             // in World::bodies()
    int dof = -1;               // 12-DOF block, -1 when fixed (static, kinematic)
    BodyGeometry geometry;
    AffineMass mass;
    double k_ortho = 0.0;       // kappa_ortho * volume, capped by ortho_step_ratio (barrier_params.h)
    double radius = 0.0;        // m, bounding radius about X = 0 (planes: 0)
    Material material;
    Vec12 q, q0, q_pred;
    bool restarted = false;     // started from its rigid state (no matching affine state)
    bool active = false;        // still solved by Newton (dynamic, not converged with its island)
    int slot = -1;              // its block in the Newton system while active
  };
  struct Entry {                // one primitive pair near contact
    int a = -1, b = -1;         // indices into bodies_
    PrimitivePair pair;
    PairDistance dist;
    EdgeMollifier mollifier;    // edge-edge pairs: IPC's factor for nearly parallel edges
    double shift = 0.0;         // m, subtracted from dist.d
    bool apart = false;         // shifted, but apart (d > touch) at the step's start
    bool placed = false;        // a placed pair (the header's "Bodies placed touching")
    double width = 0.0;         // m, the barrier's activation distance: d_hat, or w when placed
    double scale = 1.0;         // of kappa: d_hat / width, so a placed pair's forces are the barrier's
    double depth = 0.0;         // m, EvaluatePair's signed depth: to below the pair's zero
  };
  struct Shift {                // a pair's zero at the step's start, by KeyOf
    double shift = 0.0;         // m
    bool apart = false;
    bool placed = false;
  };
  struct Friction {             // lagged at the step's start
    int a = -1, b = -1;
    Vec3 Xa, Xb;
    Eigen::Matrix<double, 3, 2> T;
    double mu_lambda = 0.0;     // N
  };

  // The bodies solved together in one line search: connected by a pair of
  // the line, a pair within d_hat or a friction pair (barrier_newton.cpp).
  struct Island {
    std::vector<int> bodies;    // indices into bodies_
    std::vector<int> line;      // indices into the line's entries
    std::vector<int> friction;  // indices into friction_
  };

  void Setup(World& world, const BarrierParams& params);
  // The shifted zeros of the step: the placed pairs kept from the last
  // step, the new placed pairs of the bodies that start, and the pairs
  // closer than the floor (the header's derivation).
  void TakeShifts(const World& world);
  // Primitive pairs with d - shift < d_hat at the bodies' q, of the pairs
  // with an active body; with `step`, every such pair that can come within
  // d_hat on the way to q + step (pair_search.h), evaluated at q.
  void Collect(const std::vector<Vec12>* step, std::vector<Entry>* out);
  // Distance and mollifier of an entry at the bodies' q.
  void Evaluate(Entry* e) const;
  // The entries of `line` (a Collect along the step just taken) within d_hat at q.
  void Refresh(const std::vector<Entry>& line, std::vector<Entry>* out) const;
  CcdPair CcdPairOf(const Entry& e, const std::vector<Vec12>& step) const;
  // kappa at the step's start (IPC sec. 4.3; the header's derivation).
  void InitialKappa(const World& world, const std::vector<Entry>& entries);

  // barrier_newton.cpp: the Newton iterations over the active bodies.
  // Numbers the active bodies' 12-DOF blocks; their count.
  int AssignSlots();
  // Gradient and projected Hessian of the incremental potential in the
  // active bodies' blocks, from the pairs in `entries` and the friction lag.
  void Assemble(const std::vector<Entry>& entries, NewtonSystem* system) const;
  // The islands of the active bodies along `step` (`line` its pairs).
  std::vector<Island> Islands(const std::vector<Entry>& line, const std::vector<Entry>& entries);
  // Inertia, orthogonality, barrier and friction energy of one island.
  double IslandEnergy(const Island& island, const std::vector<Entry>& line) const;
  // The line search of one island along `step`: the CCD bound, then halving
  // until its energy decreases. False (q unchanged) when no alpha did.
  bool LineSearch(const Island& island, const std::vector<Vec12>& step, const std::vector<Entry>& line);
  // Moves each island along `step` by its own line search (an island whose
  // step is below the tolerance, when `converge`, is converged instead and
  // leaves the active set), refreshes `entries` at the new q, doubles kappa
  // while the closest pair keeps closing below the floor, and brings back
  // the frozen bodies whose neighbourhood moved. Returns whether any island
  // failed its line search.
  bool AdvanceIslands(const std::vector<Vec12>& step, bool converge, std::vector<Entry>* line,
                      std::vector<Entry>* entries, double* last_min);
  // Makes the frozen bodies active again whose neighbourhood changed: a body
  // that `moved` shares a pair of `line` or a friction pair with them, or
  // kappa changed under their barrier pairs; re-collects `entries` then.
  void WakeNeighbours(const std::vector<Entry>& line, const std::vector<char>& moved, bool kappa_changed,
                      std::vector<Entry>* entries);
  // Moves each body that turns fast enough from q_n towards its q_pred by
  // AdvanceIslands, before the Newton iterations (affine_prediction.h). q_pred's
  // rotation is on the rotation manifold, while from A_n each Newton step
  // leaves it along its tangent and the stiff orthogonality potential slows
  // the return: a free box spinning at 1.7 rad/s took 7 iterations a step
  // and its rotation still lagged by 3e-7, |L| drifting 4% in 10 s; started
  // at q_pred, the step ends there. Fast enough: the tangent step's stretch
  // at a vertex, r |A_pred - A_n|^2 / 2, is above what Newton resolves,
  // tolerance h (a vertex speed above sqrt(2 r tolerance / h), 0.07 m/s for
  // r = 0.1 m at 240 Hz); slower, starting at q_n costs nothing, and the
  // wobble of box_pyramid's boxes (1e-3 to 1e-2 m/s) started at q_pred took
  // 43.1 Newton iterations a step against 39.6. The whole q_pred, not only
  // its rotation: a rolling body's contact point keeps still only with both
  // (rotation alone, of 240 steps of a 12-box block of box_rain 44 stopped
  // unconverged at max_iterations against 23 before). A body turning slower
  // stays at q_n: one that static friction holds stays where it is when the
  // first Newton step is below the tolerance, whereas moved to p_pred, or
  // turned by the 3e-5 m/s a held box rocks at, Newton resolves the smoothed
  // friction's creep (up to 0.06 mm/s on a 30 degree slope with mu 0.7,
  // barrier_params.h) and the box slid 0.05-0.12 mm in 2 s.
  void StartTurningBodiesAtPrediction(std::vector<Vec12>* step, std::vector<Entry>* line,
                                      std::vector<Entry>* entries, double* last_min);
  // Newton's iterations until every body has converged or max_iterations.
  void Minimise(std::vector<Entry>* entries, double* last_min, BarrierStepResult* result);
  // Makes every dynamic body active again.
  void ActivateAll();
  // Translates each cluster of dynamic bodies joined by `pairs` (of bodies_
  // indices), `entries` or the friction pairs, and touching no fixed body,
  // so that its momentum is the implicit step's: sum m (p - p_pred) = 0
  // (barrier_momentum.cpp); true when it moved a body.
  bool BalanceMomentum(std::vector<std::pair<int, int>> pairs, const std::vector<Entry>& entries);

  // Writes q back to the rigid bodies, and the contacts within d_hat.
  void WriteBack(World& world, const std::vector<Entry>& entries, ContactSet* contacts,
                 BarrierStepResult* result) const;
  // Lagged friction of the pairs in `entries` at the bodies' q.
  void Lag(const std::vector<Entry>& entries);
  // Whether the lag `now` at a solution is the lag `used` to find it: each
  // pair of bodies' sum of mu lambda within `tolerance` of the largest.
  static bool LagSettled(const std::vector<Friction>& used, const std::vector<Friction>& now, double tolerance);
  // The previous step's lagged friction, for bodies still present.
  void LagFromState(const World& world);
  // Stores the bodies' affine state and the end-of-step friction lag.
  void Remember(const World& world, const std::vector<Entry>& entries);
  double EffectiveDistance(const Entry& e) const { return e.dist.d - e.shift; }
  // m, the distance that keeps an entry among the candidates (< d_hat): a
  // placed pair's true one counts too, so it stays placed while within d_hat
  double SearchDistance(const Entry& e) const {
    return e.placed ? std::min(e.dist.d, EffectiveDistance(e)) : EffectiveDistance(e);
  }
  // m, how far behind a face a point still counts as inside (EvaluatePair):
  // past the lowest shifted zero, -floor
  double SignedDepth() const;

  static constexpr double kFloor = 1e-2;  // of d_hat: pairs closer at the start are shifted; kappa grows below it
  static constexpr double kTouch = 1e-6;  // of d_hat: a shifted pair farther apart at the start was not touching
  static constexpr double kPlacedWidth = 2e-2;  // of d_hat: a placed pair's activation width, and its zero below its start
  static constexpr double kPlacedReach = 0.5;  // of d_hat: a pair starting closer is placed (its resting range)
  static constexpr double kPlacedDepth = 2.0;   // of d_hat: the deepest overlap a placed pair is measured from
  // of d_hat: how far a triangle surface is searched around a primitive
  // (surface_primitives.h); beyond, the distance is reported as this, which
  // the additive CCD of a body falling 12 mm a step crosses in a few advances
  static constexpr double kSurfaceReach = 10.0;

  BarrierParams params_;
  const World* world_ = nullptr;  // the stepped world, from Setup: its bodies' filters
  double h_ = 0.0;
  double kappa_ = 0.0;
  double kappa_max_ = 0.0;
  std::vector<Body> bodies_;
  // shifts of the pairs that started too close, by (a, b, kind, ia, ib, swapped)
  std::map<std::tuple<int, int, int, int, int, bool>, Shift> shift_;
  std::vector<Friction> friction_;
  int dofs_ = 0;
  NewtonSystem system_;
  PrimitivePairSearch search_;
  std::vector<SearchBody> search_bodies_;
  std::vector<CandidatePair> candidates_;
  BarrierState state_;
};

}  // namespace contactsim
