#include "service/contact/xpbd/xpbd_restitution.h"

#include <cmath>

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// The points that take part in the stage: pushed in the sub-step, not
// jointed (the velocity pass's block restitution, through the articulation).
bool TakesPart(const XpbdPoint& p) { return p.lambda_n > 0.0 && p.w_n > 0.0 && !p.jointed; }

void MarkStruck(int a, int b, const std::vector<SoftBody>& bodies, std::vector<char>* struck) {
  for (int i : {a, b}) {
    if (bodies[i].inv_mass > 0.0) (*struck)[i] = 1;
  }
}

// The row's friction at the contact point, for a point without restitution
// (sequential_impacts.h): the stage's own, added to the velocity pass's
// patch friction.
void SetFrictionRows(const XpbdPoint& p, const XpbdPointFrame& frame, const std::vector<SoftBody>& bodies,
                     ImpactRow* r) {
  r->friction = p.restitution > 0.0 ? 0.0 : frame.friction;
  if (frame.friction <= 0.0) return;
  Vec3 t[2];
  PerpendicularBasis(p.n, &t[0], &t[1]);
  for (int axis : {0, 1}) {
    ImpactTangent& row = r->t[axis];
    row.d = t[axis];
    row.ra = p.ra.cross(t[axis]);
    row.rb = frame.rb.cross(t[axis]);
    row.ia = bodies[p.a].inv_inertia * row.ra;
    row.ib = bodies[p.b].inv_inertia * row.rb;
  }
}

// Marks the bodies of the `frictional` strikes whose component of bodies
// joined by the step's points no static or kinematic body holds (the stage
// takes a struck point with friction only there, sequential_impacts.h);
// looked for here, once a step, so that a held pile is not gathered in
// every sub-step. Returns whether it marked any.
bool MarkFreeStrikes(const std::vector<int>& frictional, const std::vector<XpbdPoint>& points,
                     const std::vector<SoftBody>& bodies, std::vector<char>* struck) {
  if (frictional.empty()) return false;
  const int n = static_cast<int>(bodies.size());
  UnionFind sets(n);
  std::vector<char> held(n, 0);
  for (const XpbdPoint& p : points) {
    if (p.w_n <= 0.0 || p.jointed) continue;
    if (bodies[p.a].inv_mass > 0.0 && bodies[p.b].inv_mass > 0.0) sets.Join(p.a, p.b);
  }
  for (const XpbdPoint& p : points) {
    if (p.w_n <= 0.0 || p.jointed) continue;
    if (bodies[p.a].inv_mass <= 0.0) held[sets.Root(p.b)] = 1;
    if (bodies[p.b].inv_mass <= 0.0) held[sets.Root(p.a)] = 1;
  }
  bool any = false;
  for (int i : frictional) {
    const XpbdPoint& p = points[i];
    if (held[sets.Root(bodies[p.a].inv_mass > 0.0 ? p.a : p.b)]) continue;
    MarkStruck(p.a, p.b, bodies, struck);
    any = true;
  }
  return any;
}

}  // namespace

bool MarkXpbdStrikes(double strike, const std::vector<XpbdPoint>& points, const std::vector<XpbdPointFrame>& frames,
                     const std::vector<SoftBody>& bodies, std::vector<char>* struck) {
  struck->assign(bodies.size(), 0);
  bool any = false;
  std::vector<int> frictional;  // struck points with friction and without restitution
  for (size_t i = 0; i < points.size(); ++i) {
    const XpbdPoint& p = points[i];
    if (p.w_n <= 0.0 || p.jointed) continue;
    any = any || p.restitution > 0.0;
    const SoftBody& A = bodies[p.a];
    const SoftBody& B = bodies[p.b];
    if (std::abs(XpbdNormalVelocity(p, A.v, A.w, B.v, B.w)) <= strike) continue;
    if (frames[i].friction > 0.0 && p.restitution <= 0.0) {
      frictional.push_back(static_cast<int>(i));
      continue;
    }
    MarkStruck(p.a, p.b, bodies, struck);
    any = true;
  }
  return MarkFreeStrikes(frictional, points, bodies, struck) || any;
}

bool GatherXpbdImpacts(double h, double threshold, const std::vector<NormalBlock>& blocks,
                       const std::vector<XpbdPoint>& points, const std::vector<XpbdPointFrame>& frames,
                       const std::vector<XpbdPose>& predicted, const std::vector<SoftBody>& bodies,
                       SequentialImpacts* impacts, std::vector<char>* deferred, std::vector<char>* struck) {
  deferred->assign(blocks.size(), 0);
  impacts->Begin(static_cast<int>(bodies.size()));
  for (int k = 0; k < static_cast<int>(blocks.size()); ++k) {
    for (int i = blocks[k].first; i < blocks[k].first + blocks[k].count; ++i) {
      const XpbdPoint& p = points[i];
      if (!TakesPart(p)) continue;
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
      r.struck = (*struck)[p.a] || (*struck)[p.b];
      // v~ is the velocity at which the sub-step's pairs meet: no gain
      r.impact = XpbdNormalVelocity(p, predicted[p.a].v, predicted[p.a].w, predicted[p.b].v, predicted[p.b].w);
      r.lambda = p.lambda_n / h;
      SetFrictionRows(p, frames[i], bodies, &r);
      impacts->AddRow(r);
    }
  }
  if (!impacts->FindTargets(threshold)) return false;
  for (const ImpactRow& r : impacts->rows()) {
    (*deferred)[r.group] = 1;
    MarkStruck(r.a, r.b, bodies, struck);
  }
  return true;
}

void SolveXpbdImpacts(double h, SequentialImpacts* impacts, std::vector<SoftBody>& bodies,
                      std::vector<XpbdPoint>* points) {
  impacts->Solve(bodies);
  for (const ImpactRow& r : impacts->rows()) {
    XpbdPoint& p = (*points)[r.point];
    p.impulse += (r.lambda - p.lambda_n / h) * p.n + r.t[0].lambda * r.t[0].d + r.t[1].lambda * r.t[1].d;
  }
}

}  // namespace contactsim
