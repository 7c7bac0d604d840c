// Ericson, "Real-Time Collision Detection", 2005: point-segment (5.1.2),
// segment-segment (5.1.9, ClosestPtSegmentSegment) and point-triangle
// (5.1.5, ClosestPtPointTriangle: Voronoi regions of the vertices, then the
// edges, then the face) closest points.
#include "service/collision/closest_points.h"

#include <algorithm>

namespace contactsim {
namespace {

// Squared lengths below this are degenerate segments (points); 1e-24 m^2 is
// (1e-12 m)^2, far below any shape size the server accepts.
constexpr double kDegenerateSq = 1e-24;

double Clamp01(double v) { return std::min(1.0, std::max(0.0, v)); }

}  // namespace

Vec3 ClosestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b, double* t) {
  const Vec3 ab = b - a;
  const double len_sq = ab.squaredNorm();
  const double u = len_sq > kDegenerateSq ? Clamp01((p - a).dot(ab) / len_sq) : 0.0;
  if (t != nullptr) *t = u;
  return a + u * ab;
}

SegmentClosestPoints ClosestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                             const Vec3& q2) {
  SegmentClosestPoints out;
  const Vec3 d1 = q1 - p1;
  const Vec3 d2 = q2 - p2;
  const Vec3 r = p1 - p2;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double f = d2.dot(r);
  double s = 0.0;
  double t = 0.0;
  if (a <= kDegenerateSq && e <= kDegenerateSq) {
    // both segments are points
  } else if (a <= kDegenerateSq) {
    t = Clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= kDegenerateSq) {
      s = Clamp01(-c / a);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // |d1|^2 |d2|^2 sin^2(angle) >= 0
      // parallel segments (relative sin^2 below 1e-14) keep s = 0, as Ericson
      if (denom > 1e-14 * a * e) s = Clamp01((b * f - c * e) / denom);
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = Clamp01(-c / a);
      } else if (t > 1.0) {
        t = 1.0;
        s = Clamp01((b - c) / a);
      }
    }
  }
  out.s = s;
  out.t = t;
  out.c1 = p1 + s * d1;
  out.c2 = p2 + t * d2;
  return out;
}

Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary) {
  Vec3 unused;
  Vec3& w = bary != nullptr ? *bary : unused;
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return w = Vec3(1, 0, 0), a;  // vertex a
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return w = Vec3(0, 1, 0), b;  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {  // edge ab
    const double v = d1 / (d1 - d3);
    w = Vec3(1 - v, v, 0);
    return a + v * ab;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return w = Vec3(0, 0, 1), c;  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {  // edge ac
    const double t = d2 / (d2 - d6);
    w = Vec3(1 - t, 0, t);
    return a + t * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge bc
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    w = Vec3(0, 1 - t, t);
    return b + t * (c - b);
  }
  const double denom = 1.0 / (va + vb + vc);  // inside the face
  const double v = vb * denom, t = vc * denom;
  w = Vec3(1 - v - t, v, t);
  return a + v * ab + t * ac;
}

}  // namespace contactsim
