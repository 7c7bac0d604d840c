#include "service/contact/penalty/penalty_stiffness.h"

#include <algorithm>
#include <cmath>

#include "service/collision/aabb.h"
#include "service/contact/union_find.h"

namespace contactsim {

std::vector<double> IslandHeaviestMass(const World& world, const ContactSet& contacts) {
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  UnionFind islands(n);
  for (const Contact& c : contacts) {
    if (bodies[c.a].IsDynamic() && bodies[c.b].IsDynamic()) islands.Join(c.a, c.b);
  }
  std::vector<double> heaviest(n, 0.0);
  for (int i = 0; i < n; ++i) {
    if (bodies[i].IsDynamic()) heaviest[islands.Root(i)] = std::max(heaviest[islands.Root(i)], bodies[i].mass);
  }
  std::vector<double> out(n, 0.0);
  for (int i = 0; i < n; ++i) {
    if (bodies[i].IsDynamic()) out[i] = heaviest[islands.Root(i)];
  }
  return out;
}

double StiffnessFromContactTime(double heaviest_mass, double contact_time) {
  const double omega = M_PI / contact_time;
  return heaviest_mass * omega * omega;
}

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

// The largest eigenvalue of M^-1 J^T K J (rad^2/s^2) by power iteration in
// the metric of M, where it is symmetric: u <- M^-1 J^T K J u, lambda the
// Rayleigh quotient u^T J^T K J u / u^T M u.
double PowerIteration(const World& world, const std::vector<PenaltyRow>& rows, const std::vector<bool>& counted) {
  const auto& bodies = world.bodies();
  const size_t n = bodies.size();
  std::vector<Mat3> inv_inertia(n), inertia(n);
  std::vector<Vec6> u(n, Vec6::Zero()), f(n);
  for (size_t i = 0; i < n; ++i) {
    if (!bodies[i].IsDynamic()) continue;
    inv_inertia[i] = bodies[i].InvInertiaWorld();
    inertia[i] = bodies[i].InertiaWorld();
    // a fixed start with a part along every mode
    for (int c = 0; c < 6; ++c) u[i][c] = 1.0 + 0.37 * c + 0.11 * static_cast<double>(i % 7);
  }
  auto point_velocity = [&](int b, const Vec3& r) {
    return bodies[b].IsDynamic() ? Vec3(u[b].head<3>() + u[b].tail<3>().cross(r)) : Vec3::Zero();
  };
  auto push = [&](int b, const Vec3& r, const Vec3& force) {
    if (!bodies[b].IsDynamic()) return;
    f[b].head<3>() += force;
    f[b].tail<3>() += r.cross(force);
  };
  double lambda = 0.0;
  for (int it = 0; it < kPowerIterations; ++it) {
    for (auto& v : f) v.setZero();
    double energy = 0.0;  // u^T J^T K J u
    for (size_t k = 0; k < rows.size(); ++k) {
      const PenaltyRow& row = rows[k];
      if (!counted[k]) continue;
      const Vec3 du = point_velocity(row.b, row.rb) - point_velocity(row.a, row.ra);
      const double kt = row.mu > 0.0 ? row.kt : 0.0;
      const double dn = row.n.dot(du);
      const Vec3 dt = du - row.n * dn;
      const Vec3 force = row.law.k * dn * row.n + kt * dt;
      energy += du.dot(force);
      push(row.b, row.rb, force);
      push(row.a, row.ra, -force);
    }
    double mass_norm = 0.0;  // u^T M u
    for (size_t i = 0; i < n; ++i) {
      if (!bodies[i].IsDynamic()) continue;
      mass_norm += bodies[i].mass * u[i].head<3>().squaredNorm() + u[i].tail<3>().dot(inertia[i] * u[i].tail<3>());
    }
    if (mass_norm <= 0.0) return 0.0;
    lambda = energy / mass_norm;
    // u <- M^-1 f, scaled to keep the numbers near 1
    const double scale = 1.0 / std::max(std::sqrt(mass_norm) * std::max(lambda, 1e-300), 1e-300);
    for (size_t i = 0; i < n; ++i) {
      if (!bodies[i].IsDynamic()) continue;
      u[i].head<3>() = scale * bodies[i].inv_mass * f[i].head<3>();
      u[i].tail<3>() = scale * (inv_inertia[i] * f[i].tail<3>());
    }
  }
  return lambda;
}

}  // namespace

ContactOmega ContactOmegas(const World& world, const std::vector<PenaltyRow>& rows) {
  const auto& bodies = world.bodies();
  std::vector<bool> counted(rows.size());
  double point = 0.0;  // rad^2/s^2
  double ratio = 1.0;
  for (size_t i = 0; i < rows.size(); ++i) {
    const PenaltyRow& row = rows[i];
    counted[i] = row.engaged;
    if (!row.engaged || row.m_share <= 0.0) continue;
    const double lighter = std::min(bodies[row.a].IsDynamic() ? bodies[row.a].mass : HUGE_VAL,
                                    bodies[row.b].IsDynamic() ? bodies[row.b].mass : HUGE_VAL);
    ratio = std::max(ratio, row.m_spring * row.nc / lighter);
    if (row.rebounds) {
      point = std::max(point, row.law.k / row.m_share);
    } else {
      // the mass the spring was set for, or the pair's own 2 m_eff when that
      // is lighter (a light body pressed by a heavy one: docs/methods/penalty.md)
      const double m = std::min(row.m_spring, 2.0 * row.m_share);
      point = std::max(point, row.law.k / (m * kSettleSlack * kSettleSlack));
    }
  }
  return {std::sqrt(point), std::sqrt(PowerIteration(world, rows, counted)), ratio};
}

double BoundingRadius(const RigidBody& body) {
  const Aabb box = ComputeAabb(body, 0.0, 0.0);
  return 0.5 * (box.max - box.min).norm();
}

double FastestPointSpeed(const RigidBody& body) {
  if (body.motion == MotionType::kStatic) return 0.0;
  return body.LinearVelocity().norm() + body.AngularVelocity().norm() * BoundingRadius(body);
}

double SpeculativeMargin(const World& world, double margin, double dt) {
  double fastest = 0.0;  // m/s
  for (const RigidBody& body : world.bodies()) fastest = std::max(fastest, FastestPointSpeed(body));
  return margin + dt * (2.0 * fastest + world.gravity.norm() * dt);
}

}  // namespace contactsim
