// Affine body dynamics (Lan, Kaufman, Li, Jiang and Yang 2022, "Affine Body
// Dynamics: fast, stable and intersection-free simulation of stiff
// materials", SIGGRAPH): a body has 12 degrees of freedom
//   q = (p, a1, a2, a3),  x(X) = p + A X,  A = [a1^T; a2^T; a3^T],
// for the body-frame point X (centre of mass at X = 0), so every point moves
// linearly in q and x = J(X) q with J(X) = [I, diag(X^T, X^T, X^T)]. The mass
// matrix M = integral rho J^T J dV is block diagonal,
//   M = diag(m I3, S, S, S),  S = integral rho X X^T dV = tr(I_b)/2 I - I_b,
// (the first moment vanishes at the centre of mass), so the kinetic energy
// 1/2 qdot^T M qdot of A = R, Adot = [w]x R is the rigid one. A stiff
// orthogonality potential keeps A a rotation:
//   V(A) = kappa vol ||A A^T - I||_F^2                   (eq. 7)
// with gradient 4 kappa vol sum_j (a_i . a_j - delta_ij) a_j per row a_i.
#pragma once

#include <Eigen/Core>

#include "service/physics/rigid_body.h"

namespace contactsim {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;

Vec12 AffineFromPose(const Vec3& p, const Mat3& A);
Vec3 AffinePosition(const Vec12& q);
Mat3 AffineMatrix(const Vec12& q);
// x(X) = p + A X
Vec3 AffinePoint(const Vec12& q, const Vec3& X);
// J(X)^T v: the generalised force of the world vector v acting at X
Vec12 AffineJacobianT(const Vec3& X, const Vec3& v);

// Mass blocks of a dynamic body: m and S (body frame).
struct AffineMass {
  double m = 0.0;
  Mat3 S = Mat3::Zero();
  Vec12 Times(const Vec12& v) const;     // M v
  Vec12 Solve(const Vec12& f) const;     // M^-1 f
  Mat12 Matrix() const;
};
AffineMass AffineMassOf(const RigidBody& body);

// The state of a rigid body as affine coordinates and their velocity
// (A = R, Adot = [w]x R).
void RigidToAffine(const RigidBody& body, Vec12* q, Vec12* qdot);

// The rigid pose nearest to A: R from the polar decomposition A = R S
// (SVD A = U Sigma V^T, R = U V^T with the sign of det fixed).
Mat3 NearestRotation(const Mat3& A);

// Orthogonality potential, its gradient and its Hessian projected to
// positive semi-definite (negative eigenvalues clamped to zero), all with
// the stiffness k = kappa * volume (N m).
double OrthogonalityEnergy(const Vec12& q, double k);
void OrthogonalityDerivatives(const Vec12& q, double k, Vec12* gradient, Mat12* hessian);

}  // namespace contactsim
