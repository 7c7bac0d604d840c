#include "service/contact/xpbd/xpbd_restitution.h"

namespace contactsim {

bool GatherXpbdImpacts(double h, double threshold, const std::vector<NormalBlock>& blocks,
                       const std::vector<XpbdPoint>& points, const std::vector<XpbdPose>& predicted,
                       const std::vector<SoftBody>& bodies, SequentialImpacts* impacts, std::vector<char>* deferred) {
  deferred->assign(blocks.size(), 0);
  impacts->Begin(static_cast<int>(bodies.size()));
  for (int k = 0; k < static_cast<int>(blocks.size()); ++k) {
    for (int i = blocks[k].first; i < blocks[k].first + blocks[k].count; ++i) {
      const XpbdPoint& p = points[i];
      if (p.lambda_n <= 0.0 || p.w_n <= 0.0) continue;  // did not push in the sub-step
      if (p.jointed) continue;  // the velocity pass's block restitution, through the articulation
      for (int b : {p.a, p.b}) {
        if (!impacts->HasBody(b)) impacts->SetBody(b, predicted[b].v, predicted[b].w, bodies[b].inv_mass);
      }
      ImpactRow r;
      r.point = i;
      r.group = k;
      r.a = p.a, r.b = p.b;
      r.n = p.n, r.ra_n = p.ra_n, r.rb_n = p.rb_n, r.ia_n = p.ia_n, r.ib_n = p.ib_n;
      r.mass_n = 1.0 / p.w_n;
      r.restitution = p.restitution;
      // v~ is the velocity at which the sub-step's pairs meet: no gain
      r.impact = XpbdNormalVelocity(p, predicted[p.a].v, predicted[p.a].w, predicted[p.b].v, predicted[p.b].w);
      r.lambda = p.lambda_n / h;
      impacts->AddRow(r);
    }
  }
  if (!impacts->FindTargets(threshold)) return false;
  for (const ImpactRow& r : impacts->rows()) (*deferred)[r.group] = 1;
  return true;
}

void SolveXpbdImpacts(double h, SequentialImpacts* impacts, std::vector<SoftBody>& bodies,
                      std::vector<XpbdPoint>* points) {
  impacts->Solve(bodies);
  for (const ImpactRow& r : impacts->rows()) {
    XpbdPoint& p = (*points)[r.point];
    p.impulse += (r.lambda - p.lambda_n / h) * p.n;
  }
}

}  // namespace contactsim
