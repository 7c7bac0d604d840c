// Contacts as constraint rows for the velocity-level LCP (Stewart and
// Trinkle 1996; Anitescu and Potra 1997): per contact one normal row and
// two friction rows along tangents t1, t2: those of contact_row.h (a basis
// that depends only on n, so that it is the same from step to step);
// AlignFrictionRows turns them to the contact's predicted slip (below).
//
// Normal row, J v = n . (v_B(p) - v_A(p)) = vn, lambda in [0, inf):
//   * colliding (vn- < -restitution_threshold, vn- the approach speed at the
//     step's start, before forces): the impact is traced back to its moment
//     (PredictImpact below) and rhs = the normal velocity the pair has at
//     the step's end after bouncing there, -e vc + a (h - t);
//     a gap of a pair with e > 0 that the approach does not close within
//     the step (the impact lies beyond it, or never comes) is no collision
//     yet and keeps the speculative rule below: a bounce there would turn
//     the body round in mid-air, short of the surface, every time it falls
//     back (a tetrahedron with e = 0.5 hovered in a cycle of three steps
//     0.7-1 mm above the ground at 0.055 m/s, the speculative contact found
//     within the 1 mm slop); otherwise, if tracing fails (see
//     PredictImpact), rhs = -e vn- (Newton's law of restitution at the
//     velocity level), which for e = 0 stops such a gap's approach for the
//     step: passive, and kept (the speculative rule there changed a
//     random scene of mixed masses under lemke into one whose light box
//     was thrown through the ground, not traced further);
//   * a gap (depth < 0, a speculative contact within the slop):
//     rhs = depth / h, the bodies may close the gap in this step, no more;
//   * otherwise rhs = 0, plus erp (depth - slop) / h with drift = baumgarte
//     (Baumgarte stabilisation: it turns penetration into separating
//     velocity, which adds kinetic energy; drift = split, the default, moves
//     positions instead, see lcp_method.h).
// Friction rows, rhs = 0, |lambda_t| <= mu lambda_n (normal_row, mu): PGS
// projects the pair onto the disk (pgs.h), so its basis does not matter.
// Lemke's rows bound each tangent alone, a four-sided pyramid
// (lemke_rows.h), which gives Coulomb's mu lambda_n only along t1 and t2
// and up to sqrt(2) mu lambda_n between them. For Lemke the rows are
// turned (AlignFrictionRows): t1 is the direction of the tangential relative velocity u* of the
// velocities after this step's forces, before contact (v* = v + h M^-1 f),
// t2 = n x t1, as Bullet's solver aligns its first friction direction with
// the lateral velocity (btSequentialImpulseConstraintSolver): the impulse
// that stops or slows the slip lies along t1, where the pyramid's bound is
// exactly mu lambda_n. That is exact for a contact whose slip keeps its
// direction through the solve (a body sliding, or held on a slope, by
// itself: u* is the direction the friction impulse opposes); where other
// contacts turn the slip within the step, the friction can exceed
// mu lambda_n by at most the pyramid's factor sqrt(2) (docs/methods/lcp.md).
// Below kSlipFloor the contact frame's basis is kept.
// Material rules are those of contact_row.h (e = max, mu = geometric mean).
//
// Why the impact time: contacts are found at the step's start, after the
// pair has passed the surface by up to |vn| h. Newton's law applied there
// to vn- (which gravity has increased since the impact) and a full step
// x += v+ h from the penetrated pose put the body too high with too much
// speed: a ball dropped 0.9 m with e = 0.5 at h = 1/240 s rebounded 3%
// (up to 7% for other drop heights) above e^2 h0. Under the step's constant
// relative normal acceleration a = (vn* - vn-) / h (vn* after forces), the
// gap g(t) = -depth + vn- t + a t^2 / 2 vanished at t = 2 depth / (vn- + vc) <= 0
// with speed vc = -sqrt(vn-^2 + 2 a depth); after Newton's law there the
// pair flies apart, so at the step's end (s = h - t after the impact) its
// normal velocity is -e vc + a s and its gap -e vc s + a s^2 / 2. The row
// gets the velocity; the position the symplectic update x += v h would miss
// is end_offset = t (e vc + vn-) + a (t^2 - h^2 / 2), added along n by the
// split impulse before the solve (it moves positions only). This is the
// impulse method's backtracking to the time of impact (Mirtich 1996),
// closed-form for constant force instead of root finding, so the contact
// state after the step is that of the exact trajectory. Impacts that do
// not bounce (-e vc at most restitution_threshold, e = 0 among them), whose
// rebound lands again in the same step (gap at the end <= 0), or that no
// approach within one step explains keep the old rule, so resting contact,
// stacks and e = 0 are unchanged.
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/collision/parallel_runner.h"
#include "service/contact/constraint_row.h"
#include "service/physics/world.h"

namespace contactsim {

struct ContactRowOptions {
  double h = 1.0 / 240.0;               // s
  double restitution_threshold = 0.01;  // m/s
  double slop = 1e-3;                   // m
  double baumgarte_erp = 0.0;           // 1/step; 0 without Baumgarte
};

// m/s: a predicted slip slower than this keeps the contact frame's tangents
constexpr double kSlipFloor = 1e-9;

// The exact state after a colliding contact's impact (see above); exact =
// false when the step-start rule applies instead.
struct Impact {
  bool exact = false;
  // a gap (depth < 0) of a pair with e > 0 that the approach does not
  // close within the step: the row keeps the speculative rule, rhs =
  // depth / h, and makes no bounce
  bool misses = false;
  double end_velocity = 0.0;  // m/s: the normal row's rhs
  double end_offset = 0.0;    // m: separation to add to the positions
};

// depth of the contact at the step's start (m, > 0 penetrating), vn_before
// and vn_free its normal velocity before and after this step's forces.
Impact PredictImpact(double depth, double vn_before, double vn_free, double restitution,
                     const ContactRowOptions& options);

// PredictImpact for every contact, in contact order; `free` holds the body
// velocities after this step's forces, v* = v + h M^-1 f. The contacts
// are split over the runner's threads, each writing its own impact.
void PredictImpacts(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                    const std::vector<SolverBody>& free, const ContactRowOptions& options, ParallelRunner& runner,
                    std::vector<Impact>* impacts);

// A row along unit d at contact point p between bodies a and b (-1: world).
ConstraintRow DirectionRow(int a, int b, const Vec3& ra, const Vec3& rb, const Vec3& d);
// The same written into *row, every field (rows kept from the last step
// are overwritten in place, without a row made and copied).
void SetDirectionRow(int a, int b, const Vec3& ra, const Vec3& rb, const Vec3& d, ConstraintRow* row);

// *rows becomes three rows per contact in contact order: normal, t1, t2
// (every field written, so rows kept from the last step cost no
// construction: zeroing 15,000 new rows was 1.8% of a box_rain step). `before`
// holds the body velocities at the step's start (restitution); the row
// Jacobians use the world's current poses; `impacts` from PredictImpacts.
// The friction rows act at `friction_points` (patch_torsion.h; null: at
// the contact points). The contacts are split over the runner's threads,
// each writing its own three rows.
void WriteContactRows(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                       const std::vector<Impact>& impacts, const ContactRowOptions& options,
                       const std::vector<Vec3>* friction_points, ParallelRunner& runner,
                       std::vector<ConstraintRow>* rows);

// Turns the friction rows of the contacts (rows 3k + 1, 3k + 2, as
// WriteContactRows wrote them) so that t1 lies along each contact's
// predicted slip at the velocities `free` (after this step's forces), the
// slip where its friction acts.
void AlignFrictionRows(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& free,
                       const std::vector<Vec3>* friction_points, std::vector<ConstraintRow>* rows);

}  // namespace contactsim
