// One contact prepared for an impulse solver: lever arms, tangent basis and
// the effective masses along the normal and the two tangents.
//
// For a unit direction d the effective mass is 1 / K_d with
//   K_d = 1/ma + 1/mb + d . (Ia^-1 (ra x d)) x ra + d . (Ib^-1 (rb x d)) x rb,
// the denominator of the impulse formula (Hahn 1988; Mirtich 1996).
#pragma once

#include <cstring>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/solver_body.h"

namespace contactsim {

struct ContactRow {
  int a = -1, b = -1;          // body indices
  Vec3 ra, rb;                 // m, contact point minus centre of mass, world
  Vec3 fa, fb;                 // m, where the friction acts minus centre of mass: ra, rb, or a
                               // patch's point moved toward its centroid (patch_torsion.h)
  Vec3 n, t1, t2;              // unit, world; n from A to B
  double k_n = 0.0;            // 1/kg: K along n
  double mass_n = 0.0;         // kg: 1 / K_n
  double mass_t1 = 0.0, mass_t2 = 0.0;
  double k_t12 = 0.0;          // 1/kg: K's coupling of t1 and t2 (slip_friction_step.h)
  double friction = 0.0;       // combined Coulomb coefficient
  double restitution = 0.0;    // combined coefficient
  double lambda_n = 0.0;       // N s accumulated along n (>= 0)
  double lambda_t1 = 0.0, lambda_t2 = 0.0;  // N s accumulated along t1, t2

  // relative velocity of B against A at the contact, along n
  double NormalVelocity(const std::vector<SolverBody>& s) const {
    return n.dot(s[b].PointVelocity(rb) - s[a].PointVelocity(ra));
  }
  Vec3 RelativeVelocity(const std::vector<SolverBody>& s) const {
    return s[b].PointVelocity(rb) - s[a].PointVelocity(ra);
  }
  // the same where the friction acts
  Vec3 FrictionVelocity(const std::vector<SolverBody>& s) const {
    return s[b].PointVelocity(fb) - s[a].PointVelocity(fa);
  }
  // +J on B, -J on A
  void Apply(const Vec3& J, std::vector<SolverBody>& s) const {
    s[b].ApplyImpulse(J, rb);
    s[a].ApplyImpulse(-J, ra);
  }
  // a tangent impulse Jt where the friction acts
  void ApplyFriction(const Vec3& Jt, std::vector<SolverBody>& s) const {
    s[b].ApplyImpulse(Jt, fb);
    s[a].ApplyImpulse(-Jt, fa);
  }
};

// Pair material rule: restitution = max(e_a, e_b) (the bouncier surface
// decides, as in Bullet and PhysX's "max" mode), friction = sqrt(mu_a mu_b)
// (geometric mean, as in Bullet and Box2D).
double CombineRestitution(const Material& a, const Material& b);
double CombineFriction(const Material& a, const Material& b);

// friction_point (world) null: the friction acts at c.point.
ContactRow MakeContactRow(const Contact& c, const World& world, const std::vector<SolverBody>& s,
                          const Vec3* friction_point = nullptr);
// The same without the effective masses (k_n, mass_*: left 0), for
// solvers that take them from their own rows (the lcp method).
ContactRow MakeContactBasis(const Contact& c, const World& world);
// Whether contact c has pair (a, b) and normal n bit for bit: a
// manifold's points share them, and MakeContactBasis then makes the same
// tangents and materials, which a caller may keep from the point before.
inline bool SharesContactFrame(const Contact& c, int a, int b, const Vec3& n) {
  return c.a == a && c.b == b && std::memcmp(c.normal.data(), n.data(), sizeof(Vec3)) == 0;
}

// K_d for direction d at the row's lever arms, and at its friction's.
double EffectiveInverseMass(const ContactRow& row, const Vec3& d, const std::vector<SolverBody>& s);
double FrictionInverseMass(const ContactRow& row, const Vec3& d, const std::vector<SolverBody>& s);

}  // namespace contactsim
