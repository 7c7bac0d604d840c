#include "service/contact/lcp/resting_contact.h"

#include <string>

#include "service/contact/lcp/delassus.h"
#include "service/contact/lcp/lcp_contact_rows.h"
#include "service/contact/lcp/lemke.h"

namespace contactsim {
namespace {

// Acceleration of the material point at r from the centre of mass under
// the body's accumulated force and torque alone.
Vec3 PointAcceleration(const RigidBody& body, const Vec3& r) {
  if (!body.IsDynamic()) return Vec3::Zero();
  const Vec3 w = body.AngularVelocity();
  const Vec3 alpha = body.InvInertiaWorld() * (body.torque + body.L.cross(w));
  return body.force * body.inv_mass + alpha.cross(r) + w.cross(w.cross(r));
}

}  // namespace

Status SolveRestingContact(const World& world, const ContactSet& contacts, RestingContactResult* out) {
  std::vector<SolverBody> bodies;
  LoadSolverBodies(world, &bodies);
  std::vector<ConstraintRow> rows;
  const int n = static_cast<int>(contacts.size());
  VecX b(n);
  for (int i = 0; i < n; ++i) {
    const Contact& c = contacts[i];
    const RigidBody& A = world.bodies()[c.a];
    const RigidBody& B = world.bodies()[c.b];
    const Vec3 ra = c.point - A.x, rb = c.point - B.x;
    rows.push_back(DirectionRow(c.a, c.b, ra, rb, c.normal));
    const Vec3 ndot = A.AngularVelocity().cross(c.normal);
    b[i] = c.normal.dot(PointAcceleration(B, rb) - PointAcceleration(A, ra)) +
           2.0 * ndot.dot(B.PointVelocity(c.point) - A.PointVelocity(c.point));
  }
  const MatX Amat = DenseDelassus(rows, bodies);
  out->lcp = SolveLemke(Amat, b);
  if (out->lcp.outcome != LcpOutcome::kSolved) {
    return Status::FailedPrecondition(std::string("resting contact LCP: Lemke ended with ") +
                                      LcpOutcomeName(out->lcp.outcome));
  }
  out->forces.assign(out->lcp.z.data(), out->lcp.z.data() + n);
  out->accelerations = out->lcp.w;
  return Status::Ok();
}

}  // namespace contactsim
