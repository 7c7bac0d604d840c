#include "service/contact/barrier/edge_mollifier.h"

namespace contactsim {
namespace {

// dm/dq of a world edge u = A U moved by the rows of A: (0, g_x U, g_y U, g_z U)
Vec12 EdgeGradient(const Vec3& U, const Vec3& g_u) {
  Vec12 g = AffineJacobianT(U, g_u);
  g.head<3>().setZero();
  return g;
}

// The rest edge vector of edge k of g.
Vec3 RestEdge(const BodyGeometry& g, int k) { return g.points[g.edges[k][1]] - g.points[g.edges[k][0]]; }

}  // namespace

double EdgeMollifierValue(const Vec3& Ua, const Vec3& Ub, const Vec3& u, const Vec3& v) {
  const double eps_x = 1e-3 * Ua.squaredNorm() * Ub.squaredNorm();
  const double c = u.cross(v).squaredNorm();
  if (c >= eps_x) return 1.0;
  const double s = c / eps_x;
  return s * (2.0 - s);
}

EdgeMollifier MollifyEdgeEdge(const BodyGeometry& a, const Mat3& Aa, const BodyGeometry& b, const Mat3& Ab,
                              const PrimitivePair& pair, const PairDistance& dist) {
  EdgeMollifier out;
  Vec3 Ua, Ub;
  if (pair.kind == PrimitiveKind::kEdgeEdge) {
    Ua = RestEdge(a, pair.ia);
    Ub = RestEdge(b, pair.ib);
  } else if (pair.kind == PrimitiveKind::kEdgeSurface) {
    // the body's edge and the surface's chosen one, on their sides
    Ua = pair.swapped ? dist.surface_edge : RestEdge(a, pair.ia);
    Ub = pair.swapped ? RestEdge(b, pair.ia) : dist.surface_edge;
  } else {
    return out;
  }
  const double eps_x = 1e-3 * Ua.squaredNorm() * Ub.squaredNorm();
  const Vec3 u = Aa * Ua, v = Ab * Ub;
  const Vec3 w = u.cross(v);
  const double c = w.squaredNorm();
  if (c >= eps_x) return out;
  const double s = c / eps_x;
  out.m = s * (2.0 - s);
  // dc = 2 (v x w) . du + 2 (w x u) . dv, dm/dc = (2 - 2 s) / eps_x
  const double dm_dc = (2.0 - 2.0 * s) / eps_x;
  out.grad_a = EdgeGradient(Ua, dm_dc * 2.0 * v.cross(w));
  out.grad_b = EdgeGradient(Ub, dm_dc * 2.0 * w.cross(u));
  return out;
}

}  // namespace contactsim
