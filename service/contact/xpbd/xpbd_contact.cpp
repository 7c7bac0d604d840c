#include "service/contact/xpbd/xpbd_contact.h"

#include <algorithm>
#include <cmath>

#include "service/collision/manifold_reduction.h"
#include "service/contact/contact_row.h"
#include "service/contact/xpbd/positional_correction.h"

namespace contactsim {
namespace {

// [begin, end) of each body pair's contacts (the detector appends a pair's
// manifold contiguously), at most kMaxManifoldPoints to a group so that a
// group's friction rows fit a pair block (kMaxPairRows).
std::vector<std::pair<size_t, size_t>> PairGroups(const std::vector<XpbdContact>& contacts) {
  std::vector<std::pair<size_t, size_t>> groups;
  for (size_t k = 0; k < contacts.size();) {
    size_t end = k + 1;
    while (end < contacts.size() && end - k < kMaxManifoldPoints && contacts[end].a == contacts[k].a &&
           contacts[end].b == contacts[k].b) {
      ++end;
    }
    groups.push_back({k, end});
    k = end;
  }
  return groups;
}

// A unit vector perpendicular to the unit n, depending on n alone.
Vec3 Perpendicular(const Vec3& n) {
  return std::abs(n.x()) < 0.57735 ? n.cross(Vec3::UnitX()).normalized() : n.cross(Vec3::UnitY()).normalized();
}

}  // namespace

XpbdContact MakeXpbdContact(const Contact& c, const World& world) {
  const RigidBody& A = world.bodies()[c.a];
  const RigidBody& B = world.bodies()[c.b];
  XpbdContact x;
  x.a = c.a;
  x.b = c.b;
  x.n = c.normal;
  // the surface points lie depth/2 either side of the midpoint (conventions.md)
  const Vec3 pa = c.point + 0.5 * c.depth * c.normal;
  const Vec3 pb = c.point - 0.5 * c.depth * c.normal;
  x.ra_body = A.q.conjugate() * (pa - A.x);
  x.rb_body = B.q.conjugate() * (pb - B.x);
  x.friction = CombineFriction(A.material, B.material);
  x.restitution = CombineRestitution(A.material, B.material);
  return x;
}

double XpbdContactDepth(const XpbdContact& c, const World& world, Vec3* pa_out, Vec3* pb_out) {
  const RigidBody& A = world.bodies()[c.a];
  const RigidBody& B = world.bodies()[c.b];
  const Vec3 pa = A.x + A.q * c.ra_body;
  const Vec3 pb = B.x + B.q * c.rb_body;
  if (pa_out) *pa_out = pa;
  if (pb_out) *pb_out = pb;
  return (pa - pb).dot(c.n);
}

void BeginXpbdSubstep(const World& world, std::vector<XpbdContact>* contacts) {
  for (XpbdContact& c : *contacts) {
    c.lambda_n = 0.0;
    c.lambda_t.setZero();
    Vec3 pa, pb;
    XpbdContactDepth(c, world, &pa, &pb);
    const RigidBody& A = world.bodies()[c.a];
    const RigidBody& B = world.bodies()[c.b];
    c.vn_before = c.n.dot(B.PointVelocity(pb) - A.PointVelocity(pa));
  }
}

void SolveXpbdContactPositions(World& world, const std::vector<XpbdPose>& start, double h, double alpha_tilde,
                               std::vector<XpbdContact>* contacts) {
  auto& bodies = world.bodies();
  std::vector<PairRow> rows, trows;
  std::vector<size_t> which;
  std::vector<double> rhs, trhs;
  for (const auto& [begin, end] : PairGroups(*contacts)) {
    RigidBody& A = bodies[(*contacts)[begin].a];
    RigidBody& B = bodies[(*contacts)[begin].b];
    // non-penetration of every penetrating point of the pair at once
    rows.clear();
    which.clear();
    rhs.clear();
    for (size_t k = begin; k < end; ++k) {
      XpbdContact& c = (*contacts)[k];
      Vec3 pa, pb;
      const double d = XpbdContactDepth(c, world, &pa, &pb);
      if (d <= 0.0) continue;
      rows.push_back({pa - A.x, pb - B.x, c.n});
      which.push_back(k);
      rhs.push_back(d - alpha_tilde * c.lambda_n);
    }
    if (rows.empty()) continue;
    const PairVector x = SolvePairBlock(A, B, rows, rhs, alpha_tilde, true);
    ApplyPairPositional(A, B, rows, x);
    double lambda_n = 0.0;
    for (size_t i = 0; i < which.size(); ++i) {
      XpbdContact& c = (*contacts)[which[i]];
      c.lambda_n += x(i);
      c.impulse += x(i) / h * c.n;  // a positional impulse p moves like the velocity impulse p / h
      lambda_n += c.lambda_n;
    }

    // static friction: undo the tangential slip of the points over the
    // sub-step if the pair's friction multipliers stay in mu sum(lambda_n)
    const double mu = (*contacts)[begin].friction;
    if (mu <= 0.0 || lambda_n <= 0.0) continue;
    trows.clear();
    trhs.clear();
    for (size_t k : which) {
      const XpbdContact& c = (*contacts)[k];
      Vec3 pa, pb;
      XpbdContactDepth(c, world, &pa, &pb);
      const Vec3 dp = (pa - (start[c.a].x + start[c.a].q * c.ra_body)) - (pb - (start[c.b].x + start[c.b].q * c.rb_body));
      const Vec3 t1 = Perpendicular(c.n), t2 = c.n.cross(t1);
      trows.push_back({pa - A.x, pb - B.x, t1});
      trows.push_back({pa - A.x, pb - B.x, t2});
      trhs.push_back(dp.dot(t1) - alpha_tilde * c.lambda_t.dot(t1));
      trhs.push_back(dp.dot(t2) - alpha_tilde * c.lambda_t.dot(t2));
    }
    const PairVector xt = SolvePairBlock(A, B, trows, trhs, alpha_tilde, false);
    double lambda_t = 0.0;
    for (size_t i = 0; i < which.size(); ++i) {
      const XpbdContact& c = (*contacts)[which[i]];
      lambda_t += (c.lambda_t + xt(2 * i) * trows[2 * i].d + xt(2 * i + 1) * trows[2 * i + 1].d).norm();
    }
    if (lambda_t >= mu * lambda_n) continue;  // beyond the cone: the pair slides
    ApplyPairPositional(A, B, trows, xt);
    for (size_t i = 0; i < which.size(); ++i) {
      XpbdContact& c = (*contacts)[which[i]];
      const Vec3 p = xt(2 * i) * trows[2 * i].d + xt(2 * i + 1) * trows[2 * i + 1].d;
      c.lambda_t += p;
      c.impulse += p / h;
    }
  }
}

namespace {

// A body's velocities and world inverse inertia, computed once for a pair's
// velocity pass and kept in step with the impulses applied to the body
// (w = I_W^-1 L, so L += r x J gives w += I_W^-1 (r x J)).
struct PairBodyMotion {
  explicit PairBodyMotion(const RigidBody& b)
      : dynamic(b.IsDynamic()), inv_mass(b.inv_mass), inv_I(b.InvInertiaWorld()), v(b.LinearVelocity()),
        w(b.AngularVelocity()) {}
  Vec3 PointVelocity(const Vec3& r) const { return v + w.cross(r); }
  // w of the body for an impulse along the unit t at lever arm r (eq. 2-3)
  double InverseMass(const Vec3& r, const Vec3& t) const {
    if (!dynamic) return 0.0;
    const Vec3 rt = r.cross(t);
    return inv_mass + rt.dot(inv_I * rt);
  }
  void Apply(RigidBody& body, const Vec3& J, const Vec3& r) {
    if (!dynamic) return;
    body.ApplyImpulse(J, body.x + r);
    v += inv_mass * J;
    w += inv_I * r.cross(J);
  }
  bool dynamic;
  double inv_mass;
  Mat3 inv_I;
  Vec3 v, w;
};

}  // namespace

void SolveXpbdContactVelocities(World& world, double h, double restitution_threshold,
                                std::vector<XpbdContact>* contacts) {
  auto& bodies = world.bodies();
  std::vector<PairRow> rows;
  std::vector<size_t> which;
  std::vector<double> rhs;
  for (const auto& [begin, end] : PairGroups(*contacts)) {
    RigidBody& A = bodies[(*contacts)[begin].a];
    RigidBody& B = bodies[(*contacts)[begin].b];
    PairBodyMotion ma(A), mb(B);
    // restitution: the pushing points of the pair leave at max(-e v~_n, 0) together
    rows.clear();
    which.clear();
    rhs.clear();
    for (size_t k = begin; k < end; ++k) {
      const XpbdContact& c = (*contacts)[k];
      if (c.lambda_n <= 0.0) continue;
      Vec3 pa, pb;
      XpbdContactDepth(c, world, &pa, &pb);
      const Vec3 ra = pa - A.x, rb = pb - B.x;
      const double vn = c.n.dot(mb.PointVelocity(rb) - ma.PointVelocity(ra));
      const double e = std::abs(c.vn_before) > restitution_threshold ? c.restitution : 0.0;
      rows.push_back({ra, rb, c.n});
      which.push_back(k);
      rhs.push_back(std::max(-e * c.vn_before, 0.0) - vn);
    }
    if (rows.empty()) continue;
    const PairVector x = SolvePairBlock(A, B, rows, rhs, 0.0, false);
    for (size_t i = 0; i < which.size(); ++i) {
      const Vec3 J = x(i) * rows[i].d;
      mb.Apply(B, J, rows[i].rb);
      ma.Apply(A, -J, rows[i].ra);
      (*contacts)[which[i]].impulse += J;
    }
    // dynamic friction, point by point: the impulse that stops v_t, at most
    // mu times the point's normal impulse lambda_n / h (the paper's eq. 30
    // caps dv by h mu f_n instead, which is an impulse, not a velocity)
    for (size_t i = 0; i < which.size(); ++i) {
      XpbdContact& c = (*contacts)[which[i]];
      const Vec3 ra = rows[i].ra, rb = rows[i].rb;
      const Vec3 v = mb.PointVelocity(rb) - ma.PointVelocity(ra);
      const Vec3 vt = v - c.n * c.n.dot(v);
      const double speed = vt.norm();
      if (speed <= 0.0) continue;
      const Vec3 t = vt / speed;
      const double w = ma.InverseMass(ra, t) + mb.InverseMass(rb, t);
      if (w <= 0.0) continue;
      const Vec3 J = -t * std::min(c.friction * c.lambda_n / h, speed / w);
      mb.Apply(B, J, rb);
      ma.Apply(A, -J, ra);
      c.impulse += J;
    }
  }
}

}  // namespace contactsim
