// The positional constraint update of extended position based dynamics for
// rigid bodies (Mueller, Macklin, Chentanez, Jeschke and Kim 2020, "Detailed
// rigid body simulation with extended position based dynamics", SCA, sec.
// 3.3.1). A constraint that wants the point rb of B moved by c along the unit
// direction n relative to the point ra of A (both lever arms from the centre
// of mass, world) takes
//   w_i = 1/m_i + (r_i x n)^T I_i^-1 (r_i x n)             (eq. 2-3)
//   dlambda = (c - alpha~ lambda) / (w_a + w_b + alpha~),  alpha~ = alpha / h^2
//   p = dlambda n:  x_b += p / m_b,  q_b += 1/2 [I_b^-1 (r_b x p), 0] q_b,
//                   and -p on A                              (eq. 4-9)
// with the world inverse inertia at the current orientation. The multiplier
// lambda accumulates over a sub-step's iterations; lambda / h^2 is the force.
#pragma once

#include "service/physics/rigid_body.h"

namespace contactsim {

// w of one body for a correction along unit n at lever arm r (0 unless dynamic).
double GeneralizedInverseMass(const RigidBody& body, const Vec3& r, const Vec3& n);

// Moves a dynamic body by the positional impulse p (kg m) at lever arm r.
void ApplyPositionalImpulse(RigidBody& body, const Vec3& p, const Vec3& r);

// Rotates a dynamic body by the angular positional impulse h (kg m^2):
// q += 1/2 [I^-1 h, 0] q (eq. 10-11, for joints' angular constraints).
void ApplyAngularPositionalImpulse(RigidBody& body, const Vec3& h);

// One XPBD update of a positional constraint: moves B by +dlambda n at rb
// and A by -dlambda n at ra, adds dlambda to *lambda and returns dlambda.
// Returns 0 and changes nothing when neither body can move.
double SolvePositionalConstraint(RigidBody& a, const Vec3& ra, RigidBody& b, const Vec3& rb, const Vec3& n,
                                 double c, double alpha_tilde, double* lambda);

// The same for an angular correction by the angle c about the unit axis n
// (B turns by +c, A by -c): w_i = n^T I_i^-1 n (eq. 12-14).
double SolveAngularConstraint(RigidBody& a, RigidBody& b, const Vec3& n, double c, double alpha_tilde,
                              double* lambda);

}  // namespace contactsim
