#include "service/contact/lcp/lcp_contact_rows.h"

#include "service/contact/contact_row.h"

namespace contactsim {

ConstraintRow DirectionRow(int a, int b, const Vec3& ra, const Vec3& rb, const Vec3& d) {
  ConstraintRow row;
  row.a = a;
  row.b = b;
  // d . (v_b + w_b x rb) - d . (v_a + w_a x ra), with d . (w x r) = w . (r x d)
  row.lin_a = -d;
  row.ang_a = -ra.cross(d);
  row.lin_b = d;
  row.ang_b = rb.cross(d);
  row.lo = 0.0;
  return row;
}

void AppendContactRows(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                       const ContactRowOptions& options, std::vector<ConstraintRow>* rows) {
  for (const Contact& c : contacts) {
    const ContactRow basis = MakeContactRow(c, world, before);
    ConstraintRow normal = DirectionRow(c.a, c.b, basis.ra, basis.rb, basis.n);
    const double vn_before = basis.NormalVelocity(before);
    if (vn_before < -options.restitution_threshold) {
      normal.rhs = -basis.restitution * vn_before;
    } else if (c.depth < 0.0) {
      normal.rhs = c.depth / options.h;
    } else if (c.depth > options.slop) {
      normal.rhs = options.baumgarte_erp * (c.depth - options.slop) / options.h;
    }
    const int normal_index = static_cast<int>(rows->size());
    rows->push_back(normal);
    for (const Vec3& t : {basis.t1, basis.t2}) {
      ConstraintRow friction = DirectionRow(c.a, c.b, basis.ra, basis.rb, t);
      friction.lo = -ConstraintRow::kInf;
      friction.normal_row = normal_index;
      friction.mu = basis.friction;
      rows->push_back(friction);
    }
  }
}

}  // namespace contactsim
