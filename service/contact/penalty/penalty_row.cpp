#include "service/contact/penalty/penalty_row.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "service/contact/contact_row.h"
#include "service/contact/penalty/penalty_stiffness.h"

namespace contactsim {

Vec3 RelativeVelocity(const World& world, const PenaltyRow& row) {
  const RigidBody& A = world.bodies()[row.a];
  const RigidBody& B = world.bodies()[row.b];
  return B.LinearVelocity() + B.AngularVelocity().cross(row.rb) - A.LinearVelocity() -
         A.AngularVelocity().cross(row.ra);
}

double InverseEffectiveMass(const World& world, const PenaltyRow& row, const Vec3& d) {
  double k = 0.0;
  for (const auto& [index, r] : {std::pair<int, Vec3>(row.a, row.ra), std::pair<int, Vec3>(row.b, row.rb)}) {
    const RigidBody& body = world.bodies()[index];
    if (!body.IsDynamic()) continue;
    const Vec3 rd = r.cross(d);
    k += body.inv_mass + rd.dot(body.InvInertiaWorld() * rd);
  }
  return k;
}

namespace {

struct PairInfo {
  int index = 0;               // in the map's (deterministic) order
  int points = 0;
  double m_eff = 0.0;          // kg, 1 / (1/m_a + 1/m_b)
  double restitution = -1.0;   // combined, or -1 when kd / alpha are given
  double kp = 0.0;             // N/m (N/m^n hunt_crossley)
  double m_spring = 0.0;       // kg, the mass kp was set for
  double kt = 0.0;             // N/m, tangential spring
  double kd = 0.0;             // N s/m, linear law
  double ct = 0.0;             // N s/m, tangential dashpot
};

// Each pair's m_eff, restitution, stiffness (fixed, or from the contact
// time: penalty_stiffness.h) and the damping that gives the restitution.
void SetPairStiffnessAndDamping(const World& world, const ContactSet& contacts, const PenaltyParams& params,
                                std::map<std::pair<int, int>, PairInfo>* pairs) {
  const auto& bodies = world.bodies();
  const bool linear = params.model == "linear";
  const bool timed = linear && params.contact_time > 0.0;
  std::vector<double> heaviest;
  if (timed) heaviest = IslandHeaviestMass(world, contacts);
  std::map<double, double> zeta_of;  // restitution -> zeta: one bisection per value, not per pair
  for (auto& [key, pair] : *pairs) {
    const double inv = bodies[key.first].inv_mass + bodies[key.second].inv_mass;
    pair.m_eff = inv > 0.0 ? 1.0 / inv : 0.0;
    if (params.restitution == "material") {
      pair.restitution = CombineRestitution(bodies[key.first].material, bodies[key.second].material);
    } else if (params.restitution != "off") {
      pair.restitution = params.RestitutionValue();
    }
    pair.kp = params.kp;
    pair.kt = params.friction_stiffness;
    pair.m_spring = pair.m_eff;
    if (timed) {
      pair.m_spring = std::max(heaviest[key.first], heaviest[key.second]);
      pair.kp = StiffnessFromContactTime(pair.m_spring, params.contact_time);
      pair.kt = pair.kp;
    }
    if (linear) {
      if (pair.restitution >= 0.0) {
        const auto [it, added] = zeta_of.try_emplace(pair.restitution, 0.0);
        if (added) it->second = ZetaFromRestitution(pair.restitution);
        pair.kd = 2.0 * it->second * std::sqrt(pair.kp * pair.m_eff);  // DampingFromRestitution
      } else {
        pair.kd = params.kd;
      }
    }
    pair.ct = 2.0 * params.friction_damping_ratio * std::sqrt(pair.kt * pair.m_eff);
  }
}

// The row's rest depth (penalty_row.h) from what its anchor kept.
double RestDepth(const FrictionAnchors& anchors, const Contact& c, const PenaltyRow& row, const PenaltyParams& params,
                 const RowOptions& options) {
  const double overlap = std::max(0.0, c.depth);
  const double drained = params.overlap_push_speed * options.elapsed;
  // a placed start's compression (penalty_preload.h) is given back slowly
  if (row.had_anchor && row.anchor.rest_depth < 0.0) {
    return std::min(0.0, row.anchor.rest_depth + params.preload_drain_speed * options.elapsed);
  }
  if (row.had_anchor) return std::min(overlap, std::max(0.0, row.anchor.rest_depth - drained));
  // a new point of a pair in contact shares the pair's rest depth (the
  // manifold's points change as a placed body settles)
  double pair_rest = 0.0;
  if (anchors.PairRestDepth(c.id_a, c.id_b, &pair_rest)) {
    if (pair_rest < 0.0) return std::min(0.0, pair_rest + params.preload_drain_speed * options.elapsed);
    return std::min(overlap, std::max(0.0, pair_rest - drained));
  }
  return std::max(0.0, overlap - std::max(0.0, -row.vn0) * options.elapsed - drained);
}

}  // namespace

void BuildPenaltyRows(const World& world, const ContactSet& contacts, const PenaltyParams& params,
                      const FrictionAnchors& anchors, const RowOptions& options, std::vector<PenaltyRow>* rows) {
  const auto& bodies = world.bodies();
  const bool linear = params.model == "linear";
  rows->assign(contacts.size(), PenaltyRow());
  std::map<std::pair<int, int>, PairInfo> pairs;

  // geometry, velocities and which points carry force
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    PenaltyRow& row = (*rows)[k];
    row.contact = static_cast<int>(k);
    row.a = c.a;
    row.b = c.b;
    row.ra = c.point - bodies[c.a].x;
    row.rb = c.point - bodies[c.b].x;
    row.n = c.normal;
    // the same tangent basis as the impulse rows: it depends on n only
    row.t1 = std::abs(row.n.x()) < 0.57735 ? row.n.cross(Vec3::UnitX()).normalized()
                                           : row.n.cross(Vec3::UnitY()).normalized();
    row.t2 = row.n.cross(row.t1);
    row.depth = c.depth;
    const Vec3 v = RelativeVelocity(world, row);
    row.vn0 = row.n.dot(v);
    row.vt0 = v - row.n * row.vn0;
    // the implicit step's active set decides which gaps the step closes,
    // so every detected point of the linear law is a candidate there
    row.engaged = c.depth > 0.0 || (options.implicit && linear) || options.speculative;
    ++pairs[{std::min(c.a, c.b), std::max(c.a, c.b)}].points;
  }

  SetPairStiffnessAndDamping(world, contacts, params, &pairs);
  int index = 0;
  for (auto& entry : pairs) entry.second.index = index++;

  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    PenaltyRow& row = (*rows)[k];
    if (!row.engaged) continue;
    const PairInfo& pair = pairs[{std::min(c.a, c.b), std::max(c.a, c.b)}];
    row.nc = pair.points;
    row.pair = pair.index;
    row.had_anchor = anchors.Find(c, &row.anchor);
    const bool was_penetrating = row.had_anchor && row.anchor.penetrating;
    if (row.had_anchor) {
      row.anchor.stretch = ProjectStretch(row.anchor.stretch, row.n);
    } else {
      row.anchor = AnchorState();
      row.anchor.impact_speed = std::max(0.0, -row.vn0);
    }
    row.anchor.rest_depth = RestDepth(anchors, c, row, params, options);
    const double spring_depth = c.depth - row.anchor.rest_depth;
    row.anchor.penetrating = spring_depth > 0.0;

    double damping = 0.0;  // kd (linear) or alpha (hunt_crossley) of the pair
    if (linear) {
      damping = pair.kd;
    } else {
      damping = pair.restitution >= 0.0 ? HuntCrossleyAlpha(pair.restitution, row.anchor.impact_speed)
                                        : params.hc_damping;
    }
    row.kp = pair.kp;
    row.damping = damping;
    row.m_share = pair.m_eff / row.nc;
    row.rebounds = pair.restitution != 0.0;
    row.restitution = pair.restitution;
    row.m_spring = pair.m_spring / row.nc;
    row.law = EvaluateNormalLaw(params, spring_depth, row.vn0, row.nc, damping, pair.kp);
    if (linear && spring_depth > 0.0 && !was_penetrating && options.h > 0.0) {
      // the dashpot cannot have removed more than the approach momentum
      const double approach = std::max(0.0, -row.vn0);
      const double impulse = std::min(damping * std::min(spring_depth, approach * options.h), pair.m_eff * approach);
      row.law.lambda0 += impulse / (row.nc * options.h);
    }
    row.mu = CombineFriction(bodies[c.a].material, bodies[c.b].material);
    row.inv_mass_n = InverseEffectiveMass(world, row, row.n);
    const double slip = row.vt0.norm();
    row.inv_mass_t = InverseEffectiveMass(world, row, slip > 1e-12 ? Vec3(row.vt0 / slip) : row.t1);
    row.kt = pair.kt / row.nc;
    row.ct = pair.ct / row.nc;
  }
}

}  // namespace contactsim
