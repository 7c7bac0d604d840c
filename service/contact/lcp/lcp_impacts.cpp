#include "service/contact/lcp/lcp_impacts.h"

#include <algorithm>

#include "service/contact/contact_row.h"
#include "service/contact/normal_block.h"

namespace contactsim {
namespace {

// The cascade of a strike is followed until its pairs approach slower than
// 1e-3 of the strike (or the threshold, if that is lower), in at most 100
// passes: 0.5 m/s into six touching spheres with e = 0.5 left 0.017 v0 off
// the one-at-a-time answer with the threshold (0.01 m/s) and 20 passes.
constexpr ImpactCascade kCascade{1e-3, 100};

// Contact i's normal row as an impact row of the group (body pair and
// normal) it belongs to.
ImpactRow ImpactRowOf(int i, int group, const ConstraintRow& normal, const Contact& c, const World& world,
                      const std::vector<SolverBody>& before) {
  ImpactRow r;
  r.point = i;
  r.group = group;
  r.a = c.a, r.b = c.b;
  r.n = normal.lin_b;
  r.ra_n = -normal.ang_a;
  r.rb_n = normal.ang_b;
  r.ia_n = before[c.a].inv_inertia * r.ra_n;
  r.ib_n = before[c.b].inv_inertia * r.rb_n;
  r.mass_n = 1.0 / normal.Diagonal(before);
  r.restitution = CombineRestitution(world.bodies()[c.a].material, world.bodies()[c.b].material);
  r.impact = normal.Velocity(before);
  return r;
}

}  // namespace

bool SequenceImpacts(const ContactSet& contacts, const World& world, const std::vector<SolverBody>& before,
                     const std::vector<Impact>& impacts, double threshold, SequentialImpacts* sequence,
                     std::vector<ConstraintRow>* rows, std::vector<double>* impulses) {
  impulses->assign(contacts.size(), -1.0);
  // a world without restitution (most resting scenes) costs one look
  const auto& bodies = world.bodies();
  if (std::none_of(contacts.begin(), contacts.end(), [&](const Contact& c) {
        return CombineRestitution(bodies[c.a].material, bodies[c.b].material) > 0.0;
      })) {
    return false;
  }
  std::vector<NormalBlock> groups;
  GroupNormalBlocks(contacts, &Contact::normal, &groups);
  sequence->Begin(static_cast<int>(world.bodies().size()));
  for (int g = 0; g < static_cast<int>(groups.size()); ++g) {
    for (int i = groups[g].first; i < groups[g].first + groups[g].count; ++i) {
      const Contact& c = contacts[i];
      const ConstraintRow& normal = (*rows)[3 * i];
      if (impacts[i].misses || !(normal.Diagonal(before) > 0.0)) continue;
      for (int body : {c.a, c.b}) {
        if (!sequence->HasBody(body)) sequence->SetBody(body, before[body].v, before[body].w, before[body].inv_mass);
      }
      sequence->AddRow(ImpactRowOf(i, g, normal, c, world, before));
    }
  }
  if (!sequence->FindTargets(threshold, kCascade)) return false;
  bool any = false;
  for (const ImpactRow& r : sequence->rows()) {
    if (!(r.phase > 0.0)) continue;
    const Impact& impact = impacts[r.point];
    // a contact traced to its moment of impact leaves at -e vc + a s
    // (end_velocity) where the step-start law gives -e vn-: the same shift
    // on its target
    (*rows)[3 * r.point].rhs = r.target + (impact.exact ? impact.end_velocity + r.restitution * r.impact : 0.0);
    (*impulses)[r.point] = r.phase;
    any = true;
  }
  return any;
}

}  // namespace contactsim
