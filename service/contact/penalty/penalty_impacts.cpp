#include "service/contact/penalty/penalty_impacts.h"

#include <algorithm>
#include <cmath>

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// A strike is followed until its pairs approach slower than 1e-3 of it, in
// at most 100 passes (lcp_impacts.cpp: 20 passes at the threshold alone
// left six touching spheres struck at 0.5 m/s with e = 0.5 0.017 v0 off).
constexpr ImpactCascade kCascade{1e-3, 100};
// Rows apart by less than the fastest strike closes in this many sub-steps
// take part (penalty_impacts.h, step 2).
constexpr double kReachSubsteps = 2.0;

// step 1: frictionless or rebounding, approaching, and closing within the
// sub-step h (touching by its end, and compressed by no more than it
// closes: a loaded spring that rings faster than the threshold is no impact)
bool Struck(const PenaltyRow& row, const ImpactArms& arms, double threshold, double h) {
  if (!MayBeStruck(row) || arms.vn >= -threshold) return false;
  const double closing = -arms.vn * h;  // m, what the approach closes in the sub-step
  return arms.spring_depth + closing > 0.0 && arms.spring_depth <= closing;
}

ImpactRow ImpactRowOf(const World& world, const PenaltyRow& row, const ImpactArms& arms, int k) {
  const RigidBody& A = world.bodies()[row.a];
  const RigidBody& B = world.bodies()[row.b];
  ImpactRow r;
  r.point = k;
  r.group = row.pair;
  r.a = row.a, r.b = row.b;
  r.n = row.n;
  r.ra_n = arms.ra.cross(row.n);
  r.rb_n = arms.rb.cross(row.n);
  r.ia_n = A.IsDynamic() ? Vec3(A.InvInertiaWorld() * r.ra_n) : Vec3::Zero();
  r.ib_n = B.IsDynamic() ? Vec3(B.InvInertiaWorld() * r.rb_n) : Vec3::Zero();
  const double K = (A.IsDynamic() ? A.inv_mass + r.ra_n.dot(r.ia_n) : 0.0) +
                   (B.IsDynamic() ? B.inv_mass + r.rb_n.dot(r.ib_n) : 0.0);
  r.mass_n = K > 0.0 ? 1.0 / K : 0.0;
  r.restitution = row.restitution;
  r.struck = true;  // only the components of struck rows are added
  // e = 0 with friction: Coulomb within each collision's impulse (as soft's
  // and xpbd's rows); a rebounding row's impacts stay normal-only
  r.friction = row.restitution > 0.0 ? 0.0 : row.mu;
  if (r.friction <= 0.0) return r;
  for (int axis : {0, 1}) {
    ImpactTangent& t = r.t[axis];
    t.d = axis == 0 ? row.t1 : row.t2;
    t.ra = arms.ra.cross(t.d);
    t.rb = arms.rb.cross(t.d);
    t.ia = A.IsDynamic() ? Vec3(A.InvInertiaWorld() * t.ra) : Vec3::Zero();
    t.ib = B.IsDynamic() ? Vec3(B.InvInertiaWorld() * t.rb) : Vec3::Zero();
  }
  return r;
}

// A struck row with friction and e = 0 (the stage takes it only in a
// component that no static or kinematic body holds: sequential_impacts.h).
bool FreeOnly(const PenaltyRow& row) { return row.restitution == 0.0 && row.mu > 0.0; }

}  // namespace

bool MayHoldImpact(const World& world, const std::vector<PenaltyRow>& rows) {
  bool free_only = false;
  for (const PenaltyRow& row : rows) {
    if (!MayBeStruck(row)) continue;
    if (!FreeOnly(row)) return true;
    free_only = true;
  }
  if (!free_only) return false;
  // components over every engaged row: each sub-step's lie within them
  const auto& bodies = world.bodies();
  UnionFind sets(static_cast<int>(bodies.size()));
  for (const PenaltyRow& row : rows) {
    if (row.engaged && bodies[row.a].IsDynamic() && bodies[row.b].IsDynamic()) sets.Join(row.a, row.b);
  }
  auto root = [&](const PenaltyRow& row) { return sets.Root(bodies[row.a].IsDynamic() ? row.a : row.b); };
  std::vector<char> held(bodies.size(), 0);
  for (const PenaltyRow& row : rows) {
    if (row.engaged && !(bodies[row.a].IsDynamic() && bodies[row.b].IsDynamic())) held[root(row)] = 1;
  }
  for (const PenaltyRow& row : rows) {
    if (MayBeStruck(row) && !held[root(row)]) return true;
  }
  return false;
}

double PenaltyImpactThreshold(const World& world, double impact_threshold) {
  return std::max(impact_threshold, 2.0 * world.gravity.norm() * world.dt);
}

bool PenaltyImpacts::Resolve(World& world, std::vector<PenaltyRow>& rows, const std::vector<ImpactArms>& arms,
                             double threshold, double h, double dt) {
  // step 1, and the fastest strike (m/s)
  double fastest = 0.0;
  for (size_t k = 0; k < rows.size(); ++k) {
    if (Struck(rows[k], arms[k], threshold, h)) {
      fastest = std::max(fastest, -arms[k].vn);
    }
  }
  if (fastest == 0.0) return false;
  // step 2: components over the rows within the strike's reach
  auto& bodies = world.bodies();
  const double reach = kReachSubsteps * fastest * h;
  auto near = [&](const PenaltyRow& row) {
    return row.engaged && row.restitution >= 0.0 && row.depth - row.anchor.rest_depth > -reach;
  };
  UnionFind sets(static_cast<int>(bodies.size()));
  for (const PenaltyRow& row : rows) {
    if (near(row) && bodies[row.a].IsDynamic() && bodies[row.b].IsDynamic()) sets.Join(row.a, row.b);
  }
  auto root = [&](const PenaltyRow& row) { return sets.Root(bodies[row.a].IsDynamic() ? row.a : row.b); };
  // a held component's frictional strikes are left to the springs here,
  // so that a pile under gravity is not gathered for the stage to drop
  held_.assign(bodies.size(), 0);
  for (const PenaltyRow& row : rows) {
    if (near(row) && !(bodies[row.a].IsDynamic() && bodies[row.b].IsDynamic())) held_[root(row)] = 1;
  }
  struck_.assign(bodies.size(), 0);
  bool any_struck = false;
  for (size_t k = 0; k < rows.size(); ++k) {
    if (!Struck(rows[k], arms[k], threshold, h)) continue;
    const int c = root(rows[k]);
    if (FreeOnly(rows[k]) && held_[c]) continue;
    struck_[c] = 1;
    any_struck = true;
  }
  if (!any_struck) return false;
  impacts_.Begin(static_cast<int>(bodies.size()));
  for (size_t k = 0; k < rows.size(); ++k) {
    const PenaltyRow& row = rows[k];
    if (!near(row) || !struck_[root(row)]) continue;
    for (int i : {row.a, row.b}) {
      if (impacts_.HasBody(i)) continue;
      const RigidBody& b = bodies[i];
      impacts_.SetBody(i, b.LinearVelocity(), b.AngularVelocity(), b.IsDynamic() ? b.inv_mass : 0.0);
    }
    impacts_.AddRow(ImpactRowOf(world, row, arms[k], static_cast<int>(k)));
  }
  // step 3: the phase's impulses onto the bodies
  if (!impacts_.FindTargets(threshold, kCascade)) return false;
  bool any = false;
  for (const ImpactRow& r : impacts_.rows()) {
    if (!(r.phase > 0.0)) continue;
    any = true;
    RigidBody& A = bodies[r.a];
    RigidBody& B = bodies[r.b];
    // the normal impulse and the friction it carried
    Vec3 p = r.phase * r.n;
    Vec3 la = r.phase * r.ra_n, lb = r.phase * r.rb_n;
    if (r.friction > 0.0) {  // r.t is set only then
      for (const ImpactTangent& t : r.t) p += t.phase * t.d, la += t.phase * t.ra, lb += t.phase * t.rb;
    }
    if (A.IsDynamic()) A.P -= p, A.L -= la;
    if (B.IsDynamic()) B.P += p, B.L += lb;
    // step 4: the spring starts where the impact left it
    PenaltyRow& row = rows[r.point];
    row.impulse += r.phase;
    if (arms[r.point].spring_depth > 0.0) row.anchor.rest_depth = std::max(row.anchor.rest_depth, row.depth);
  }
  return any;
}

}  // namespace contactsim
