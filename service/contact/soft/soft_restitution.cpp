#include "service/contact/soft/soft_restitution.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

// Of the restitution threshold, the normal speed below which a point that
// pushed is at rest: sequential_impacts.cpp's kRestTolerance, the accuracy
// its solve stops at where every target is about 0.
constexpr double kRestShare = 1e-5;

// A body's velocities at the step's start: v = P / m, w = R0 I_body^-1 R0^T L
// at its starting orientation.
void AddStartVelocities(const World& world, const std::vector<SoftBody>& bodies, int i, SequentialImpacts* impacts) {
  if (impacts->HasBody(i)) return;
  const RigidBody& b = world.bodies()[i];
  const SoftBody& s = bodies[i];
  if (!b.IsDynamic()) {
    impacts->SetBody(i, b.LinearVelocity(), b.AngularVelocity(), 0.0);
    return;
  }
  const Mat3 R0 = s.R0t.transpose();
  impacts->SetBody(i, b.inv_mass * b.P, R0 * (b.inv_inertia_body * (s.R0t * b.L)), s.inv_mass);
}

}  // namespace

bool SoftPointStruck(double threshold, const SoftPoint& p, const std::vector<SoftBody>& bodies) {
  if (p.impact_speed < -threshold) return true;
  return p.NormalVelocity(bodies[p.a], bodies[p.b]) > threshold;
}

bool SoftStepNeedsRestitution(double threshold, const std::vector<SoftPoint>& points,
                              const std::vector<SoftBody>& bodies) {
  for (const SoftPoint& p : points) {
    // no body to move: K = 1/m_A + 1/m_B + ... = 0, the rows' mass_n 0
    // (read from the bodies, as the float path prepares the points without
    // their rows: soft_contact.h)
    if (p.total_n <= 0.0 || bodies[p.a].inv_mass + bodies[p.b].inv_mass <= 0.0) continue;
    if (p.restitution != 0.0) {
      if (p.impact_speed < -threshold) return true;
      const double vn = p.NormalVelocity(bodies[p.a], bodies[p.b]);
      if (std::abs(vn) > kRestShare * threshold) return true;
    } else if (SoftPointStruck(threshold, p, bodies)) {
      return true;
    }
  }
  return false;
}

void RestituteSoftPoints(double threshold, const World& world, const std::vector<SoftManifold>& manifolds,
                         std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies, SequentialImpacts* impacts) {
  if (!SoftStepNeedsRestitution(threshold, points, bodies)) return;
  impacts->Begin(static_cast<int>(bodies.size()));
  for (int k = 0; k < static_cast<int>(manifolds.size()); ++k) {
    for (int i = manifolds[k].first; i < manifolds[k].first + manifolds[k].count; ++i) {
      const SoftPoint& p = points[i];
      if (p.total_n <= 0.0 || p.mass_n <= 0.0) continue;  // carried no impulse in the step
      AddStartVelocities(world, bodies, p.a, impacts);
      AddStartVelocities(world, bodies, p.b, impacts);
      ImpactRow r;
      r.point = i;
      r.group = k;
      r.a = p.a, r.b = p.b;
      r.n = p.n, r.ra_n = p.ra_n, r.rb_n = p.rb_n, r.ia_n = p.ia_n, r.ib_n = p.ib_n;
      r.mass_n = p.mass_n;
      r.restitution = p.restitution;
      r.struck = SoftPointStruck(threshold, p, bodies);
      r.impact = p.impact_speed;
      r.lambda = p.total_n;
      r.friction = p.restitution > 0.0 ? 0.0 : p.friction;
      r.t[0] = {p.t1, p.ra_t1, p.rb_t1, p.ia_t1, p.ib_t1};
      r.t[1] = {p.t2, p.ra_t2, p.rb_t2, p.ia_t2, p.ib_t2};
      impacts->AddRow(r);
    }
  }
  if (!impacts->FindTargets(threshold)) return;
  impacts->Solve(bodies);
  for (const ImpactRow& r : impacts->rows()) {
    SoftPoint& p = points[r.point];
    p.total_n = r.lambda;
    p.total_t1 += r.t[0].lambda;
    p.total_t2 += r.t[1].lambda;
  }
}

}  // namespace contactsim
