#include "service/contact/barrier/additive_ccd.h"

#include <algorithm>

#include "service/contact/barrier/surface_primitives.h"

namespace contactsim {
namespace {

constexpr int kMaxAdvances = 32;   // each advance is safe; the cap only costs alpha
constexpr double kClose = 0.05;    // stop when the gap to the target is this part of the start gap

double DistanceAt(const CcdPair& p, double t) {
  const Vec12 qa = p.qa + t * p.dqa, qb = p.qb + t * p.dqb;
  return EvaluatePair(*p.a, AffinePosition(qa), AffineMatrix(qa), *p.b, AffinePosition(qb), AffineMatrix(qb), p.pair, p.signed_depth,
                      {p.shift, p.width}).d -
         p.shift;
}

}  // namespace

double RelativeMotionBound(const CcdPair& p) {
  const PairVertices v = PrimitiveVertices(*p.a, *p.b, p.pair);
  std::array<Vec3, 3> da, db;
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < v.na; ++k) mean += da[k] = AffinePoint(p.dqa, v.a[k]);
  for (int k = 0; k < v.nb; ++k) mean += db[k] = AffinePoint(p.dqb, v.b[k]);
  // (a point against a static plane: nothing moves on the plane's side, so
  // no common motion can be taken out)
  mean = v.na > 0 && v.nb > 0 ? Vec3(mean / (v.na + v.nb)) : Vec3::Zero();
  double la = 0.0, lb = 0.0;
  for (int k = 0; k < v.na; ++k) la = std::max(la, (da[k] - mean).norm());
  for (int k = 0; k < v.nb; ++k) lb = std::max(lb, (db[k] - mean).norm());
  return la + lb;
}

double SeparateMotionBound(const CcdPair& p) {
  const PairVertices v = PrimitiveVertices(*p.a, *p.b, p.pair);
  double la = 0.0, lb = 0.0;
  for (int k = 0; k < v.na; ++k) la = std::max(la, AffinePoint(p.dqa, v.a[k]).norm());
  for (int k = 0; k < v.nb; ++k) lb = std::max(lb, AffinePoint(p.dqb, v.b[k]).norm());
  return la + lb;
}

double AdditiveCcd(const CcdPair& p, double fraction, double limit) {
  const double d0 = DistanceAt(p, 0.0);
  // a pair measured from a shifted zero (shift < 0) that is apart keeps its
  // true distance d0 + shift above the fraction of its value, not only the
  // shifted one: the shift lets d reach -floor, and only kappa's growth
  // kept such pairs out of it; a placed pair's zero is its own, a width
  // below where it was placed, and it may come down to it
  const double apart = d0 + p.shift;
  const double target = !p.placed && p.shift < 0.0 && apart > 0.0 ? fraction * apart - p.shift : fraction * d0;
  if (p.pair.kind == PrimitiveKind::kPointPlane) {
    // against a static plane the signed distance is linear in alpha: exact
    const double approach = d0 - DistanceAt(p, 1.0);
    return approach > 0.0 ? std::min(limit, (d0 - target) / approach) : limit;
  }
  if (IsSurfaceKind(p.pair.kind)) {
    // over a flat part of a surface: the plane's bound (surface_primitives.h)
    const bool body_is_a = !p.pair.swapped;
    double alpha = limit;
    if (FlatSurfaceCcd(body_is_a ? *p.a : *p.b, body_is_a ? p.qa : p.qb, body_is_a ? p.dqa : p.dqb,
                       body_is_a ? *p.b : *p.a, body_is_a ? p.qb : p.qa, p.pair, target + p.shift, limit, &alpha)) {
      return alpha;
    }
  }
  const double l = RelativeMotionBound(p);
  if (l <= 0.0) return limit;
  double t = 0.0, gap = d0 - target;
  for (int k = 0; k < kMaxAdvances; ++k) {
    t += gap / l;
    if (t >= limit) return limit;
    gap = DistanceAt(p, t) - target;
    if (gap <= kClose * (d0 - target)) break;
  }
  return t;
}

}  // namespace contactsim
