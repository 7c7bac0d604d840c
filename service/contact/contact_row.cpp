#include "service/contact/contact_row.h"

#include <algorithm>
#include <cmath>

namespace contactsim {

double CombineRestitution(const Material& a, const Material& b) {
  return std::max(a.restitution, b.restitution);
}

double CombineFriction(const Material& a, const Material& b) { return std::sqrt(a.friction * b.friction); }

namespace {

double InverseMassAt(const SolverBody& A, const SolverBody& B, const Vec3& ra, const Vec3& rb, const Vec3& d) {
  const Vec3 ra_d = ra.cross(d);
  const Vec3 rb_d = rb.cross(d);
  // d . (I^-1 (r x d)) x r == (r x d) . I^-1 (r x d)
  return A.inv_mass + B.inv_mass + ra_d.dot(A.inv_inertia * ra_d) + rb_d.dot(B.inv_inertia * rb_d);
}

}  // namespace

double EffectiveInverseMass(const ContactRow& row, const Vec3& d, const std::vector<SolverBody>& s) {
  return InverseMassAt(s[row.a], s[row.b], row.ra, row.rb, d);
}

double FrictionInverseMass(const ContactRow& row, const Vec3& d, const std::vector<SolverBody>& s) {
  return InverseMassAt(s[row.a], s[row.b], row.fa, row.fb, d);
}

ContactRow MakeContactBasis(const Contact& c, const World& world) {
  const RigidBody& A = world.bodies()[c.a];
  const RigidBody& B = world.bodies()[c.b];
  ContactRow row;
  row.a = c.a;
  row.b = c.b;
  row.ra = c.point - A.x;
  row.rb = c.point - B.x;
  row.fa = row.ra;
  row.fb = row.rb;
  row.n = c.normal;
  PerpendicularBasis(row.n, &row.t1, &row.t2);
  row.friction = CombineFriction(A.material, B.material);
  row.restitution = CombineRestitution(A.material, B.material);
  return row;
}

ContactRow MakeContactRow(const Contact& c, const World& world, const std::vector<SolverBody>& s,
                          const Vec3* friction_point) {
  ContactRow row = MakeContactBasis(c, world);
  if (friction_point != nullptr) {
    row.fa = *friction_point - world.bodies()[c.a].x;
    row.fb = *friction_point - world.bodies()[c.b].x;
  }
  row.k_n = EffectiveInverseMass(row, row.n, s);
  row.mass_n = row.k_n > 0.0 ? 1.0 / row.k_n : 0.0;
  const double k1 = FrictionInverseMass(row, row.t1, s);
  const double k2 = FrictionInverseMass(row, row.t2, s);
  row.mass_t1 = k1 > 0.0 ? 1.0 / k1 : 0.0;
  row.mass_t2 = k2 > 0.0 ? 1.0 / k2 : 0.0;
  const SolverBody& A = s[row.a];
  const SolverBody& B = s[row.b];
  row.k_t12 = row.fa.cross(row.t1).dot(A.inv_inertia * row.fa.cross(row.t2)) +
              row.fb.cross(row.t1).dot(B.inv_inertia * row.fb.cross(row.t2));
  return row;
}

}  // namespace contactsim
