#include "service/contact/lcp/lcp_contact_rows.h"

#include <cmath>

#include "service/contact/contact_row.h"

namespace contactsim {

void SetDirectionRow(int a, int b, const Vec3& ra, const Vec3& rb, const Vec3& d, ConstraintRow* row) {
  row->a = a;
  row->b = b;
  // d . (v_b + w_b x rb) - d . (v_a + w_a x ra), with d . (w x r) = w . (r x d)
  row->lin_a = -d;
  row->ang_a = -ra.cross(d);
  row->lin_b = d;
  row->ang_b = rb.cross(d);
  row->rhs = 0.0;
  row->lo = 0.0;
  row->hi = ConstraintRow::kInf;
  row->normal_row = -1;
  row->mu = 0.0;
  row->lambda = 0.0;
  row->cfm = 0.0;
}

ConstraintRow DirectionRow(int a, int b, const Vec3& ra, const Vec3& rb, const Vec3& d) {
  ConstraintRow row;
  SetDirectionRow(a, b, ra, rb, d, &row);
  return row;
}

Impact PredictImpact(double depth, double vn_before, double vn_free, double restitution,
                     const ContactRowOptions& options) {
  Impact impact;
  const double h = options.h;
  if (vn_before >= -options.restitution_threshold) return impact;
  const double a = (vn_free - vn_before) / h;  // relative normal acceleration
  const double disc = vn_before * vn_before + 2.0 * a * depth;
  // a bouncy pair short of the surface at the step's end: no bounce yet
  const bool short_of_surface = depth < 0.0 && restitution > 0.0;
  if (disc <= 0.0) {  // no approach reaches the surface
    impact.misses = short_of_surface;
    return impact;
  }
  const double vc = -std::sqrt(disc);
  const double t = 2.0 * depth / (vn_before + vc);  // g(t) = 0; < 0: in the past
  impact.misses = short_of_surface && t > h;
  if (t < -h || t > h) return impact;  // not explained by one step
  const double s = h - t;
  const double e = restitution;
  // the pair must bounce (rebound speed above the threshold; not e = 0) and
  // be apart at the step's end (not landing again within the step), else
  // it is in contact and the step-start rule applies
  if (-e * vc <= options.restitution_threshold || -e * vc * s + 0.5 * a * s * s <= 0.0) return impact;
  impact.exact = true;
  impact.end_velocity = -e * vc + a * s;
  impact.end_offset = t * (e * vc + vn_before) + a * (t * t - 0.5 * h * h);
  return impact;
}

namespace {

// contacts a thread takes at a time
constexpr int kContactGrain = 128;

}  // namespace

void PredictImpacts(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                    const std::vector<SolverBody>& free, const ContactRowOptions& options, ParallelRunner& runner,
                    std::vector<Impact>* impacts) {
  impacts->resize(contacts.size());
  const auto& bodies = world.bodies();
  runner.For(static_cast<int>(contacts.size()), kContactGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      // the normal velocities only (ContactRow::NormalVelocity's sums): an
      // impact needs no tangents, which the rows' frame alone makes
      // (ContactRows), and a contact that does not approach (PredictImpact's
      // first test, most resting ones) no velocity after the forces
      const Contact& c = contacts[k];
      const Vec3 ra = c.point - bodies[c.a].x;
      const Vec3 rb = c.point - bodies[c.b].x;
      const auto normal_velocity = [&](const std::vector<SolverBody>& s) {
        return c.normal.dot(s[c.b].PointVelocity(rb) - s[c.a].PointVelocity(ra));
      };
      const double vn_before = normal_velocity(before);
      if (vn_before >= -options.restitution_threshold) {
        (*impacts)[k] = Impact();
        continue;
      }
      const double restitution = CombineRestitution(bodies[c.a].material, bodies[c.b].material);
      (*impacts)[k] = PredictImpact(c.depth, vn_before, normal_velocity(free), restitution, options);
    }
  });
}

namespace {

// *basis becomes contact k's basis with its friction's lever arms
// (patch_torsion.h). With `reuse`, *basis holds the last contact's: a
// manifold's points share their pair and normal, and when k's match it bit
// for bit its tangents and materials are kept (MakeContactBasis would make
// the same from the same normal and bodies) and only the lever arms made.
void SetFrictionBasis(const ContactSet& contacts, size_t k, const World& world,
                      const std::vector<Vec3>* friction_points, bool reuse, ContactRow* basis) {
  const Contact& c = contacts[k];
  if (reuse && SharesContactFrame(c, basis->a, basis->b, basis->n)) {
    basis->ra = basis->fa = c.point - world.bodies()[c.a].x;
    basis->rb = basis->fb = c.point - world.bodies()[c.b].x;
  } else {
    *basis = MakeContactBasis(c, world);
  }
  if (friction_points != nullptr) {
    basis->fa = (*friction_points)[k] - world.bodies()[basis->a].x;
    basis->fb = (*friction_points)[k] - world.bodies()[basis->b].x;
  }
}

ContactRow FrictionBasis(const ContactSet& contacts, size_t k, const World& world,
                         const std::vector<Vec3>* friction_points) {
  ContactRow basis;
  SetFrictionBasis(contacts, k, world, friction_points, false, &basis);
  return basis;
}

// The friction directions of a contact (see the header): the contact
// frame's, or t1 along the predicted slip u*.
void SlipDirections(const ContactRow& basis, const std::vector<SolverBody>& free, Vec3* t1, Vec3* t2) {
  *t1 = basis.t1;
  *t2 = basis.t2;
  const Vec3 u = basis.FrictionVelocity(free);
  const Vec3 slip = u - basis.n.dot(u) * basis.n;
  const double speed = slip.norm();
  if (!(speed > kSlipFloor)) return;
  *t1 = slip / speed;
  *t2 = basis.n.cross(*t1);
}

}  // namespace

namespace {

// Contact k's three rows: normal, t1, t2, the normal at `first`; *frame
// holds the last contact's basis (if *has_frame), and then contact k's.
void ContactRows(const ContactSet& contacts, size_t k, const World& world, const std::vector<SolverBody>& before,
                 const Impact& impact, const ContactRowOptions& options, const std::vector<Vec3>* friction_points,
                 int first, ConstraintRow* out, ContactRow* frame, bool* has_frame) {
  const Contact& c = contacts[k];
  SetFrictionBasis(contacts, k, world, friction_points, *has_frame, frame);
  *has_frame = true;
  const ContactRow& basis = *frame;
  ConstraintRow& normal = out[0];
  SetDirectionRow(c.a, c.b, basis.ra, basis.rb, basis.n, &normal);
  // the approach speed only where no impact decided the rhs
  const double vn_before = impact.exact || impact.misses ? 0.0 : basis.NormalVelocity(before);
  if (impact.exact) {
    normal.rhs = impact.end_velocity;
  } else if (impact.misses) {
    normal.rhs = c.depth / options.h;
  } else if (vn_before < -options.restitution_threshold) {
    normal.rhs = -basis.restitution * vn_before;
  } else if (c.depth < 0.0) {
    normal.rhs = c.depth / options.h;
  } else if (c.depth > options.slop) {
    normal.rhs = options.baumgarte_erp * (c.depth - options.slop) / options.h;
  }
  const Vec3 tangents[2] = {basis.t1, basis.t2};
  for (int j = 0; j < 2; ++j) {
    ConstraintRow& friction = out[1 + j];
    SetDirectionRow(c.a, c.b, basis.fa, basis.fb, tangents[j], &friction);
    friction.lo = -ConstraintRow::kInf;
    friction.normal_row = first;
    friction.mu = basis.friction;
  }
}

}  // namespace

void WriteContactRows(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                       const std::vector<Impact>& impacts, const ContactRowOptions& options,
                       const std::vector<Vec3>* friction_points, ParallelRunner& runner,
                       std::vector<ConstraintRow>* rows) {
  rows->resize(3 * contacts.size());
  runner.For(static_cast<int>(contacts.size()), kContactGrain, [&](int begin, int end, int) {
    ContactRow frame;
    bool has_frame = false;
    for (int k = begin; k < end; ++k) {
      const int first = 3 * k;
      ContactRows(contacts, k, world, before, impacts[k], options, friction_points, first, &(*rows)[first], &frame,
                  &has_frame);
    }
  });
}

void AlignFrictionRows(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& free,
                       const std::vector<Vec3>* friction_points, std::vector<ConstraintRow>* rows) {
  for (size_t k = 0; k < contacts.size(); ++k) {
    const ContactRow basis = FrictionBasis(contacts, k, world, friction_points);
    Vec3 t[2];
    SlipDirections(basis, free, &t[0], &t[1]);
    for (int j = 0; j < 2; ++j) {
      ConstraintRow& row = (*rows)[3 * k + 1 + j];
      const ConstraintRow turned = DirectionRow(row.a, row.b, basis.fa, basis.fb, t[j]);
      row.lin_a = turned.lin_a;
      row.ang_a = turned.ang_a;
      row.lin_b = turned.lin_b;
      row.ang_b = turned.ang_b;
    }
  }
}

}  // namespace contactsim
