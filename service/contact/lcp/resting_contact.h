// Baraff's acceleration-level resting-contact problem (Baraff 1994, "Fast
// contact force computation for nonpenetrating rigid bodies", SIGGRAPH;
// Witkin and Baraff 1997, "Rigid body dynamics" notes, section 8), kept for
// comparison with the velocity-level method: frictionless, at one instant.
//
// For contacts whose relative normal velocity is zero, the normal
// accelerations depend linearly on the normal forces f:
//   ddot(d) = A f + b,  ddot(d) >= 0,  f >= 0,  f . ddot(d) = 0,
// with a_ij = n_i . (acceleration difference at contact i per unit force
// along n_j at contact j), which is the Delassus matrix J M^-1 J^T of the
// normal rows (delassus.h), and b_i the normal acceleration without contact
// forces (Baraff's eq. for b_i):
//   b_i = n_i . (pddot_B - pddot_A) + 2 ndot_i . (pdot_B - pdot_A),
//   pddot = F/m + alpha x r + w x (w x r),  alpha = I^-1 (tau + L x w),
//   ndot_i = w_A x n_i (the normal is taken as fixed in body A, whose face
//   it is: A is the plane for body-plane pairs).
// The LCP is solved by Lemke's method (A is positive semi-definite, so
// Lemke finds a solution whenever one exists; with four corners of a box
// on a plane A is singular and f is not unique, but A f and the net force
// are).
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/contact/lcp/lcp_problem.h"
#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

struct RestingContactResult {
  std::vector<double> forces;  // N, along each contact's normal, on B (-f on A)
  VecX accelerations;          // m/s^2, ddot(d) per contact after the forces
  LcpSolution lcp;
};

// Uses each body's accumulated force and torque (World::AccumulateForces).
// FailedPrecondition when Lemke fails (the outcome names why).
Status SolveRestingContact(const World& world, const ContactSet& contacts, RestingContactResult* out);

}  // namespace contactsim
