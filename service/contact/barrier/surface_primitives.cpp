#include "service/contact/barrier/surface_primitives.h"

#include <algorithm>

#include <limits>

#include "service/collision/triangle_surface.h"
#include "service/contact/barrier/barrier_potential.h"
#include "service/contact/barrier/edge_mollifier.h"

namespace contactsim {
namespace {

// The nearest candidate so far, in the surface's frame S (its body frame).
struct Nearest {
  double d = std::numeric_limits<double>::infinity();  // m, minus the body's radius
  double score = -1.0;          // an edge's mollified barrier m b
  Vec3 n12 = -Vec3::UnitZ();    // unit, S, from the body's closest point to the surface's
  Vec3 X1 = Vec3::Zero();       // the body's closest point, its body frame
  Vec3 X2 = Vec3::Zero();       // the surface's, S
  Vec3 edge = Vec3::Zero();     // the surface's edge (an edge pair)
  bool is_signed = false;
};

Vec3 Direction(const Vec3& v, const Vec3& fallback) {
  const double len = v.norm();
  return len > 0.0 ? Vec3(v / len) : fallback;
}

// The box (S) of n points grown by `grow`.
Aabb BoxAround(const Vec3* v, int n, double grow) {
  Aabb box{v[0], v[0]};
  for (int k = 1; k < n; ++k) {
    box.min = box.min.cwiseMin(v[k]);
    box.max = box.max.cwiseMax(v[k]);
  }
  box.Inflate(grow);
  return box;
}

// A point against the surface's triangles.
void NearestToPoint(const Shape& surface, const Vec3& x, const Vec3& X, double r, double grow, double signed_depth,
                    Nearest* best) {
  ForEachSurfaceTriangle(surface, BoxAround(&x, 1, grow), [&](const SurfaceTriangle& t) {
    const TriangleGap g = PointTriangleGap(x, t.v[0], t.v[1], t.v[2], signed_depth);
    const double d = (g.is_signed ? g.s : (g.c - x).norm()) - r;
    if (d >= best->d) return;
    best->d = d;
    best->is_signed = g.is_signed;
    best->n12 = g.is_signed ? Vec3(-g.n_out) : Direction(g.c - x, -t.normal);
    best->X1 = X;
    best->X2 = g.c;
  });
}

// An edge (a0, a1 in S; Y0, Y1 its body-frame ends) against the surface's
// convex edges: the largest mollified barrier, then the nearest.
void NearestToEdge(const Shape& surface, const Vec3& a0, const Vec3& a1, const Vec3& Y0, const Vec3& Y1, double r,
                   double grow, double signed_depth, const PairBarrier& barrier, Nearest* best) {
  const Vec3 ends[2] = {a0, a1};
  ForEachSurfaceTriangle(surface, BoxAround(ends, 2, grow), [&](const SurfaceTriangle& t) {
    for (int k = 0; k < 3; ++k) {
      if (!(t.convex_edges & (1u << k))) continue;
      const Vec3& b0 = t.v[k];
      const Vec3& b1 = t.v[(k + 1) % 3];
      const EdgeGap g = EdgeEdgeGap(a0, a1, b0, b1, -t.normal, signed_depth);
      const double d = (g.is_signed ? g.s : (g.c2 - g.c1).norm()) - r;
      double score = 0.0;
      if (barrier.width > 0.0) {
        const double m = EdgeMollifierValue(Y1 - Y0, b1 - b0, a1 - a0, b1 - b0);
        score = m > 0.0 ? m * Barrier(d - barrier.shift, barrier.width) : 0.0;
      }
      if (score < best->score || (score == best->score && d >= best->d)) continue;
      best->d = d;
      best->score = score;
      best->is_signed = g.is_signed;
      best->n12 = g.is_signed ? g.n : Direction(g.c2 - g.c1, -t.normal);
      best->X1 = (1 - g.s1) * Y0 + g.s1 * Y1;
      best->X2 = g.c2;
      best->edge = b1 - b0;
    }
  });
}

// A triangle (y in S, Y its body-frame corners) against the surface's
// vertices with a convex edge.
void NearestToTriangle(const Shape& surface, const Vec3 (&y)[3], const Vec3 (&Y)[3], double r, double grow,
                       double signed_depth, Nearest* best) {
  ForEachSurfaceTriangle(surface, BoxAround(y, 3, grow), [&](const SurfaceTriangle& t) {
    for (int k = 0; k < 3; ++k) {
      // a vertex with a convex edge (the edges at v[k] are k and k - 1)
      if (!(t.convex_edges & ((1u << k) | (1u << ((k + 2) % 3))))) continue;
      const Vec3& v = t.v[k];
      const TriangleGap g = PointTriangleGap(v, y[0], y[1], y[2], signed_depth);
      const double d = (g.is_signed ? g.s : (v - g.c).norm()) - r;
      if (d >= best->d) continue;
      best->d = d;
      best->is_signed = g.is_signed;
      best->n12 = g.is_signed ? g.n_out : Direction(v - g.c, g.n_out);
      best->X1 = g.w(0) * Y[0] + g.w(1) * Y[1] + g.w(2) * Y[2];
      best->X2 = v;
    }
  });
}

}  // namespace

PairDistance EvaluateSurfacePair(const BodyGeometry& g1, const Vec3& p1, const Mat3& A1, const BodyGeometry& g2,
                                 const Vec3& p2, const Mat3& A2, const PrimitivePair& pair, double signed_depth,
                                 const PairBarrier& barrier) {
  const Shape& surface = *g2.surface.shape;
  const double reach = g2.surface.reach;
  // the body's primitive in S (the surface's map is a rigid motion)
  const Mat3 to_S = A2.transpose();
  auto in_S = [&](const Vec3& X) { return Vec3(to_S * (p1 + A1 * X - p2)); };
  const double grow = reach + g1.radius;
  Nearest best;
  switch (pair.kind) {
    case PrimitiveKind::kPointSurface: {
      const Vec3& X = g1.points[pair.ia];
      best.X1 = X;
      NearestToPoint(surface, in_S(X), X, g1.radius, grow, signed_depth, &best);
      break;
    }
    case PrimitiveKind::kEdgeSurface: {
      const auto& e = g1.edges[pair.ia];
      const Vec3& Y0 = g1.points[e[0]];
      const Vec3& Y1 = g1.points[e[1]];
      best.X1 = Y0;
      NearestToEdge(surface, in_S(Y0), in_S(Y1), Y0, Y1, g1.radius, grow, signed_depth, barrier, &best);
      break;
    }
    default: {  // kTriangleSurface
      const auto& t = g1.triangles[pair.ia];
      const Vec3 Y[3] = {g1.points[t[0]], g1.points[t[1]], g1.points[t[2]]};
      const Vec3 y[3] = {in_S(Y[0]), in_S(Y[1]), in_S(Y[2])};
      best.X1 = Y[0];
      NearestToTriangle(surface, y, Y, g1.radius, grow, signed_depth, &best);
      break;
    }
  }
  // nothing within the reach: the reach, a lower bound of the distance
  if (!(best.d < reach)) {
    best.d = reach;
    best.is_signed = false;
  }
  PairDistance out = OrientPair(best.d, A2 * best.n12, best.X1, best.X2, pair.swapped);
  out.is_signed = best.is_signed;
  out.surface_edge = best.edge;
  return out;
}

bool FlatSurfaceCcd(const BodyGeometry& g1, const Vec12& q1, const Vec12& dq1, const BodyGeometry& g2,
                    const Vec12& q2, const PrimitivePair& pair, double target, double limit, double* alpha) {
  constexpr double kCoplanar = 1e-9;  // m and 1 - cos: triangles this close to one plane are in it
  // the primitive's vertices in S at both ends of the motion
  const PrimitivePair own{pair.kind, pair.ia, pair.ib, false};
  const PairVertices pv = PrimitiveVertices(g1, g2, own);
  const Mat3 to_S = AffineMatrix(q2).transpose();
  const Vec3 p2 = AffinePosition(q2);
  Vec3 ends[6];
  for (int k = 0; k < pv.na; ++k) {
    ends[2 * k] = to_S * (AffinePoint(q1, pv.a[k]) - p2);
    ends[2 * k + 1] = to_S * (AffinePoint(q1 + dq1, pv.a[k]) - p2);
  }
  bool flat = true, any = false;
  Vec3 n = Vec3::UnitZ(), o = Vec3::Zero();
  ForEachSurfaceTriangle(*g2.surface.shape, BoxAround(ends, 2 * pv.na, g2.surface.reach + g1.radius),
                         [&](const SurfaceTriangle& t) {
                           if (!any) n = t.normal, o = t.v[0], any = true;
                           flat = flat && t.normal.dot(n) > 1.0 - kCoplanar;
                           for (const Vec3& v : t.v) flat = flat && std::abs(n.dot(v - o)) < kCoplanar;
                         });
  if (!flat) return false;
  *alpha = limit;
  if (!any) return true;  // nothing within reach of the path
  for (int k = 0; k < pv.na; ++k) {
    const double s0 = n.dot(ends[2 * k] - o) - g1.radius, s1 = n.dot(ends[2 * k + 1] - o) - g1.radius;
    if (s0 <= target) return false;
    if (s1 < target) *alpha = std::min(*alpha, (s0 - target) / (s0 - s1));
  }
  return true;
}

}  // namespace contactsim
