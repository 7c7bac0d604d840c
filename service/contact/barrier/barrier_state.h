// What the barrier method carries from one step to the next, and so what a
// snapshot must hold for an exact continuation (ContactMethod::SaveState):
//  * each dynamic body's affine coordinates q and velocity qdot (Lan et al.
//    2022, Affine Body Dynamics: the state is the 12 affine degrees of
//    freedom; the World's rigid pose is only their polar decomposition).
//    With them the rigid state written back from them (x, quaternion, P,
//    L): the next step predicts the translation from qdot and the rotation
//    from that quaternion and L (affine_prediction.h), and a body whose
//    state was changed from outside since (a command, another method's
//    steps after a switch) no longer matches and restarts from its rigid
//    state;
//  * the lagged friction of Li et al. 2020 (IPC sec. 5): per contact pair at
//    the end of the previous step, the closest points in the two bodies'
//    frames, the tangent basis and mu lambda with lambda the barrier force
//    kappa |b'(d)| the pair carried then;
//  * the placed pairs (barrier_solver.h, "Bodies placed touching"): per
//    primitive pair that was touching or overlapping when one of its bodies
//    (re)started, the zero its barrier is measured from, kept while the
//    pair stays within d_hat.
// Bodies are keyed by BodyId (std::map: iteration in id order, so the saved
// bytes are deterministic).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "service/contact/barrier/affine_body.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

struct AffineBodyState {
  Vec12 q = Vec12::Zero();      // (p, rows of A), m and unitless
  Vec12 qdot = Vec12::Zero();   // m/s and 1/s
  // the rigid state written back at the end of the last step
  Vec3 x = Vec3::Zero();
  Quat rotation = Quat::Identity();
  Vec3 P = Vec3::Zero(), L = Vec3::Zero();
  // true when `body` still holds exactly (bit for bit) what was written back
  bool Matches(const RigidBody& body) const;
  void Stamp(const RigidBody& body);
};

struct LaggedFriction {
  BodyId a = 0, b = 0;
  Vec3 Xa = Vec3::Zero(), Xb = Vec3::Zero();   // m, closest points, body frames
  Eigen::Matrix<double, 3, 2> T = Eigen::Matrix<double, 3, 2>::Zero();  // world tangent basis
  double mu_lambda = 0.0;                      // N
};

struct PlacedPair {
  BodyId a = 0, b = 0;
  int kind = 0, ia = 0, ib = 0;   // PrimitivePair (contact_primitives.h)
  bool swapped = false;
  double zero = 0.0;              // m, the distance its barrier is measured from
};

struct BarrierState {
  std::map<BodyId, AffineBodyState> bodies;
  std::vector<LaggedFriction> friction;
  std::vector<PlacedPair> placed;

  void Clear() {
    bodies.clear();
    friction.clear();
    placed.clear();
  }
  std::string Save() const;
  // false (and *this unchanged) on truncated or trailing bytes; bytes
  // saved before placed pairs existed end after the friction and hold none
  bool Restore(const std::string& bytes);
};

}  // namespace contactsim
