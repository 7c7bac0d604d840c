// One contact point prepared for the penalty method: lever arms, contact
// frame, relative velocity, the normal force law linearised at the start of
// the (sub-)step, the tangential spring and its anchor.
//
// nc, the number of contact points of the pair, divides the pair's kp, kd,
// kt and ct among its points (Parent ch. 7.4), so a box on four corners
// feels the same total stiffness as a sphere on one point. nc counts every
// point the detector reports (depth > -margin), not only the penetrating
// ones: a box rocking on its corners keeps nc = 4, so each corner is one
// fixed spring of kp / 4 and the force field stays conservative. Counting
// only penetrating points doubles a corner's stiffness each time its
// neighbour lifts off, which pumps energy into the rocking (measured: a box
// sliding at 3 m/s on the explicit step hopped off the plane).
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/penalty/penalty_force.h"
#include "service/contact/penalty/penalty_friction.h"
#include "service/physics/world.h"

namespace contactsim {

struct PenaltyRow {
  int contact = -1;            // index into the step's ContactSet
  int a = -1, b = -1;          // body indices
  Vec3 ra, rb;                 // m, contact point minus centres of mass, world
  Vec3 n, t1, t2;              // unit, world; n from A to B
  double depth = 0.0;          // m, > 0 penetrating
  double vn0 = 0.0;            // m/s, n . (v_B - v_A) at the point, < 0 approaching
  Vec3 vt0 = Vec3::Zero();     // m/s, tangential part of v_B - v_A
  bool engaged = false;        // takes part in this step (penetrating, or a candidate of the implicit active set)
  int pair = -1;               // index of the row's body pair among the step's pairs
  double nc = 1.0;             // contact points of the pair
  NormalLaw law;               // includes the onset correction in lambda0
  double kp = 0.0;             // N/m (N/m^n hunt_crossley): the pair's stiffness (penalty_stiffness.h)
  double damping = 0.0;        // the pair's kd (N s/m) or Hunt-Crossley alpha (s/m)
  double m_share = 0.0;        // kg: the pair's m_eff / nc, the most momentum an onset impulse may take per m/s
  double m_spring = 0.0;       // kg: the mass the pair's stiffness was set for, / nc (m_s of a contact time, else m_eff)
  bool rebounds = true;        // the pair's restitution is not 0 (or unknown: restitution = off)
  double restitution = -1.0;   // the pair's combined restitution, -1 when kd / alpha are given (off)
  double kt = 0.0, ct = 0.0;   // N/m, N s/m: tangential spring and damper of this point
  double mu = 0.0;             // combined Coulomb coefficient
  double inv_mass_n = 0.0;     // 1/kg: the point's inverse effective mass along n
  double inv_mass_t = 0.0;     // 1/kg: the same along the slip (t1 when not slipping)
  bool had_anchor = false;
  AnchorState anchor;          // stretch projected on this step's tangent plane

  // results of the step
  double lambda = 0.0;         // N, normal force on B (>= 0)
  double impulse = 0.0;        // N s, normal impulse on B of the step's impact stage (penalty_impacts.h)
  Vec3 ft = Vec3::Zero();      // N, friction force on B, world
  bool sliding = false;

  // friction force of the spring and damper before the Coulomb limit
  Vec3 TrialFriction() const { return -kt * anchor.stretch - ct * vt0; }
};

struct RowOptions {
  double h = 0.0;              // s, (sub-)step length; 0 = no onset correction here (the explicit step adds its own)
  bool implicit = false;
  bool speculative = false;    // every detected point takes part (the explicit step tracks its depth)
  double theta = 1.0;
  double elapsed = 0.0;        // s, since the anchors were kept: the step, or the implicit sub-step
};

// A pair first seen already overlapping by more than its approach could
// close in the step, -vn elapsed, was placed so (or set there, or handed
// over by another method): that excess is its points' rest depth, the
// depth at which their springs start, and it shrinks by overlap_push_speed
// elapsed a step. The overlap is pushed out at that speed instead of at the
// spring's kp d, which for 0.5 mm at a 4 ms contact time is 31 cm/s
// (docs/methods/penalty.md, "Placement overlaps"). A point that joins a
// pair already in contact takes the pair's rest depth left, which is 0 once
// the overlap is out, so a rocking body's corners touch down on full springs.

// Builds one row per contact. The linear model's dashpot starts when the
// surfaces touch; a contact first seen already at depth d missed the
// dashpot impulse kd * (d - 0) of its way in (the dashpot impulse is kd
// times the change of depth). It is added over this step as a force
// min(kd min(d, -vn h), m_eff (-vn)) / (nc h) (onset correction: the second
// bound because the dashpot cannot have removed more than the approach
// momentum), so bounce heights do not depend on where within a step the
// impact fell.
void BuildPenaltyRows(const World& world, const ContactSet& contacts, const PenaltyParams& params,
                      const FrictionAnchors& anchors, const RowOptions& options, std::vector<PenaltyRow>* rows);

// 1/ma + 1/mb + (ra x d) . Ia^-1 (ra x d) + (rb x d) . Ib^-1 (rb x d): the
// inverse effective mass of the point along the unit direction d
// (contact_row.h), for dynamic bodies only.
double InverseEffectiveMass(const World& world, const PenaltyRow& row, const Vec3& d);

// Relative velocity of B against A at the row's lever arms, world.
Vec3 RelativeVelocity(const World& world, const PenaltyRow& row);

}  // namespace contactsim
