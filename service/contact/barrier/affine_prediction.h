// The predicted state q_pred of a dynamic affine body over one barrier step
// (barrier_solver.h), and the rigid angular momentum it ends the step with.
//
// Implicit Euler on all 12 affine coordinates, q_pred = q_n + h qdot_n +
// h^2 M^-1 f, moves A along the tangent A_n + h [w]x A_n: a rotation by
// |w| h stretched by sqrt(1 + (|w| h)^2), which the orthogonality potential
// pulls back to a rotation, taking the stretch's kinetic energy with it (a
// free sphere spinning at 10 rad/s kept 74% after 1 s, a rolling sphere
// fell up to 19% behind 5/7 g sin(theta); docs/methods/barrier.md,
// "Prediction"). So the
// rotational rows of q_pred are instead the rigid rotation advanced as
// service/physics moves a free body (integrator.h, MidpointRotation): L +=
// h tau, then the implicit midpoint rule with L held fixed, which conserves
// |L| and the kinetic energy of a torque-free body. q_pred is then on the
// rotation manifold, where the orthogonality potential vanishes, so a free
// body's step ends at q_pred. The translation keeps implicit Euler,
// p_pred = p_n + h v_n + h^2 F / m (exact for a body without force).
//
// At the end of the step the rigid angular momentum is the one the midpoint
// rule would have carried from the start to the rotation the step reached
// (EndAngularMomentum): with the rotation increment q0^-1 q1 = (1, h w / 2)
// normalised, w in the body frame, and L0 + L1 = 2 I_b w, L1 = cay(-h w^) L0,
//   L1 = I_b w - h / 2 w x I_b w          (body frame at the end),
// so a free body's next prediction continues exactly where the last left.
#pragma once

#include "service/contact/barrier/affine_body.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

// q_pred of `body` (dynamic; its rigid rotation, angular momentum, force and
// torque as at the step's start) from its affine state q, qdot, for a step h.
Vec12 PredictAffine(const RigidBody& body, const Vec12& q, const Vec12& qdot, double h);

// World angular momentum at the end of a step h that turned `body` (its
// inertia) from the rotation q0 to q1: the inverse of MidpointRotation.
Vec3 EndAngularMomentum(const RigidBody& body, const Quat& q0, const Quat& q1, double h);

}  // namespace contactsim
