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

#include <vector>

#include <Eigen/Dense>

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

namespace contactsim {

// One row of a block solve on a body pair: a unit direction d (world) at the
// lever arms ra, rb (world, from each centre of mass). +x d acts on B at rb,
// -x d on A at ra.
struct PairRow {
  Vec3 ra, rb, d;
};

// A pair block has at most two rows (the friction tangents) for each of a
// manifold's points (kMaxManifoldPoints = 4); fixed-capacity storage keeps
// the block solves, a few thousand per sub-step, off the heap.
constexpr int kMaxPairRows = 8;
using PairMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxPairRows, kMaxPairRows>;
using PairVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxPairRows, 1>;

// The pair's coupling matrix (Delassus operator) of the rows (at most
// kMaxPairRows):
//   K_kl = sum over A, B of (1/m d_k . d_l + (r_k x d_k)^T I^-1 (r_l x d_l)),
// the change of row k's relative displacement (or velocity) per unit x_l.
PairMatrix PairCoupling(const RigidBody& a, const RigidBody& b, const std::vector<PairRow>& rows);

// The minimum-norm x of (K + alpha~ I) x = rhs with K = PairCoupling (a
// face's four corners give a rank-3 K: min-norm spreads the load evenly);
// with `nonnegative`, rows whose x would be negative are dropped (x = 0) and
// the rest solved again.
PairVector SolvePairBlock(const RigidBody& a, const RigidBody& b, const std::vector<PairRow>& rows,
                          const std::vector<double>& rhs, double alpha_tilde, bool nonnegative);

// Moves the pair by the positional impulses x_k along the rows, all at once.
void ApplyPairPositional(RigidBody& a, RigidBody& b, const std::vector<PairRow>& rows, const PairVector& x);

}  // namespace contactsim
