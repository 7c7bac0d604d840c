#include "service/contact/barrier/contact_primitives.h"

#include "service/collision/closest_points.h"
#include "service/collision/posed_polyhedron.h"
#include "service/contact/barrier/surface_primitives.h"
#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

// Faces of a hull as triangle fans (faces are convex, counter-clockwise).
void AddHull(const ConvexHull& hull, const std::vector<Vec3>& points, BodyGeometry* g) {
  g->points = points;
  g->edges = hull.edges;
  for (const ConvexHull::Face& f : hull.faces) {
    for (size_t k = 1; k + 1 < f.vertices.size(); ++k) g->triangles.push_back({f.vertices[0], f.vertices[k], f.vertices[k + 1]});
  }
}

}  // namespace

bool IsSurfaceKind(PrimitiveKind kind) {
  return kind == PrimitiveKind::kPointSurface || kind == PrimitiveKind::kEdgeSurface ||
         kind == PrimitiveKind::kTriangleSurface;
}

PairDistance OrientPair(double d, const Vec3& n12, const Vec3& X1, const Vec3& X2, bool swapped) {
  PairDistance out;
  out.d = d;
  out.n = swapped ? -n12 : n12;
  out.Xa = swapped ? X2 : X1;
  out.Xb = swapped ? X1 : X2;
  return out;
}

TriangleGap PointTriangleGap(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, double signed_depth) {
  TriangleGap g;
  g.c = ClosestPointOnTriangle(p, v0, v1, v2, &g.w);
  // on the face's side or just behind it, with the foot inside the
  // triangle: the signed distance along the outward normal (faces are
  // counter-clockwise seen from outside)
  g.n_out = (v1 - v0).cross(v2 - v0).normalized();
  g.s = g.n_out.dot(p - v0);
  g.is_signed = g.s >= -signed_depth && (p - g.s * g.n_out - g.c).squaredNorm() <= 1e-24 + 1e-20 * (p - g.c).squaredNorm();
  return g;
}

EdgeGap EdgeEdgeGap(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const Vec3& toward,
                    double signed_depth) {
  EdgeGap g;
  const SegmentClosestPoints sc = ClosestPointsOfSegments(a0, a1, b0, b1);
  g.c1 = sc.c1;
  g.c2 = sc.c2;
  g.s1 = sc.s;
  g.s2 = sc.t;
  // crossing edges, closest points inside both: the signed distance along
  // e_a x e_b turned towards the second body (the separating plane of two
  // convex bodies touching edge on edge contains both edges)
  const Vec3 cross = (a1 - a0).cross(b1 - b0);
  const double sin2 = cross.squaredNorm() / ((a1 - a0).squaredNorm() * (b1 - b0).squaredNorm());
  if (sin2 > 1e-6 && sc.s > 0.0 && sc.s < 1.0 && sc.t > 0.0 && sc.t < 1.0) {
    g.n = cross.normalized();
    if (g.n.dot(toward) < 0.0) g.n = -g.n;
    g.s = g.n.dot(sc.c2 - sc.c1);
    g.is_signed = g.s >= -signed_depth;
  }
  return g;
}

BodyGeometry MakeBodyGeometry(const Shape& shape) {
  BodyGeometry g;
  switch (shape.type) {
    case ShapeType::kSphere:
      g.points = {Vec3::Zero()};
      g.radius = shape.radius;
      break;
    case ShapeType::kCapsule:
      g.points = {Vec3(0, 0, -shape.half_length), Vec3(0, 0, shape.half_length)};
      g.edges = {{0, 1}};
      g.radius = shape.radius;
      break;
    case ShapeType::kBox: {
      const ConvexHull& cube = UnitBoxTopology();
      std::vector<Vec3> points;
      for (const Vec3& v : cube.vertices) points.push_back(v.cwiseProduct(shape.half_extents));
      AddHull(cube, points, &g);
      break;
    }
    case ShapeType::kConvex:
      AddHull(*shape.hull, shape.hull->vertices, &g);
      break;
    case ShapeType::kPlane:
      g.plane = true;
      g.plane_normal = shape.plane_normal;
      g.plane_offset = shape.plane_offset;
      break;
    case ShapeType::kMesh:
    case ShapeType::kHeightfield:
      g.surface.shape = &shape;
      break;
    default: break;
  }
  return g;
}

void EnumeratePrimitivePairs(const BodyGeometry& a, const BodyGeometry& b, std::vector<PrimitivePair>* out) {
  out->clear();
  if ((a.plane || a.surface.shape) && (b.plane || b.surface.shape)) return;
  if (a.surface.shape || b.surface.shape) {
    const BodyGeometry& solid = a.surface.shape ? b : a;
    const bool swapped = a.surface.shape != nullptr;
    for (int i = 0; i < static_cast<int>(solid.points.size()); ++i) out->push_back({PrimitiveKind::kPointSurface, i, 0, swapped});
    for (int i = 0; i < static_cast<int>(solid.edges.size()); ++i) out->push_back({PrimitiveKind::kEdgeSurface, i, 0, swapped});
    for (int i = 0; i < static_cast<int>(solid.triangles.size()); ++i) {
      out->push_back({PrimitiveKind::kTriangleSurface, i, 0, swapped});
    }
    return;
  }
  if (a.plane || b.plane) {
    const BodyGeometry& solid = a.plane ? b : a;
    for (int i = 0; i < static_cast<int>(solid.points.size()); ++i) out->push_back({PrimitiveKind::kPointPlane, i, 0, a.plane});
    return;
  }
  const int na = static_cast<int>(a.points.size()), nb = static_cast<int>(b.points.size());
  for (int i = 0; i < na; ++i) {
    for (int t = 0; t < static_cast<int>(b.triangles.size()); ++t) out->push_back({PrimitiveKind::kPointTriangle, i, t, false});
  }
  for (int i = 0; i < nb; ++i) {
    for (int t = 0; t < static_cast<int>(a.triangles.size()); ++t) out->push_back({PrimitiveKind::kPointTriangle, i, t, true});
  }
  for (int e = 0; e < static_cast<int>(a.edges.size()); ++e) {
    for (int f = 0; f < static_cast<int>(b.edges.size()); ++f) out->push_back({PrimitiveKind::kEdgeEdge, e, f, false});
  }
  if (b.triangles.empty()) {
    for (int i = 0; i < na; ++i) {
      for (int e = 0; e < static_cast<int>(b.edges.size()); ++e) out->push_back({PrimitiveKind::kPointEdge, i, e, false});
    }
  }
  if (a.triangles.empty()) {
    for (int i = 0; i < nb; ++i) {
      for (int e = 0; e < static_cast<int>(a.edges.size()); ++e) out->push_back({PrimitiveKind::kPointEdge, i, e, true});
    }
  }
  if (a.edges.empty() && b.edges.empty()) {
    for (int i = 0; i < na; ++i) {
      for (int j = 0; j < nb; ++j) out->push_back({PrimitiveKind::kPointPoint, i, j, false});
    }
  }
}

PairVertices PrimitiveVertices(const BodyGeometry& a, const BodyGeometry& b, const PrimitivePair& pair) {
  PairVertices v;
  const BodyGeometry& point_side = pair.swapped ? b : a;
  const BodyGeometry& other = pair.swapped ? a : b;
  std::array<Vec3, 3> p{}, o{};
  int np = 0, no = 0;
  switch (pair.kind) {
    case PrimitiveKind::kPointTriangle:
      p[np++] = point_side.points[pair.ia];
      for (int k = 0; k < 3; ++k) o[no++] = other.points[other.triangles[pair.ib][k]];
      break;
    case PrimitiveKind::kEdgeEdge:
      for (int k = 0; k < 2; ++k) p[np++] = a.points[a.edges[pair.ia][k]];
      for (int k = 0; k < 2; ++k) o[no++] = b.points[b.edges[pair.ib][k]];
      break;
    case PrimitiveKind::kPointEdge:
      p[np++] = point_side.points[pair.ia];
      for (int k = 0; k < 2; ++k) o[no++] = other.points[other.edges[pair.ib][k]];
      break;
    case PrimitiveKind::kPointPoint:
      p[np++] = point_side.points[pair.ia];
      o[no++] = other.points[pair.ib];
      break;
    case PrimitiveKind::kPointPlane:
    case PrimitiveKind::kPointSurface:
      p[np++] = point_side.points[pair.ia];
      break;  // the plane or surface is static: no vertices move
    case PrimitiveKind::kEdgeSurface:
      for (int k = 0; k < 2; ++k) p[np++] = point_side.points[point_side.edges[pair.ia][k]];
      break;
    case PrimitiveKind::kTriangleSurface:
      for (int k = 0; k < 3; ++k) p[np++] = point_side.points[point_side.triangles[pair.ia][k]];
      break;
  }
  const bool point_is_a = !pair.swapped || pair.kind == PrimitiveKind::kEdgeEdge;
  if (point_is_a) {
    v.a = p, v.na = np, v.b = o, v.nb = no;
  } else {
    v.b = p, v.nb = np, v.a = o, v.na = no;
  }
  return v;
}

PairDistance EvaluatePair(const BodyGeometry& a, const Vec3& pa, const Mat3& Aa, const BodyGeometry& b,
                          const Vec3& pb, const Mat3& Ab, const PrimitivePair& pair, double signed_depth,
                          const PairBarrier& barrier) {
  PairDistance out;
  const bool swapped = pair.swapped && pair.kind != PrimitiveKind::kEdgeEdge;
  // the point side's and the other side's geometry and maps
  const BodyGeometry& g1 = swapped ? b : a;
  const BodyGeometry& g2 = swapped ? a : b;
  const Vec3& p1 = swapped ? pb : pa;
  const Vec3& p2 = swapped ? pa : pb;
  const Mat3& A1 = swapped ? Ab : Aa;
  const Mat3& A2 = swapped ? Aa : Ab;
  auto world1 = [&](int i) { return Vec3(p1 + A1 * g1.points[i]); };
  auto world2 = [&](int i) { return Vec3(p2 + A2 * g2.points[i]); };
  Vec3 X1 = Vec3::Zero(), X2 = Vec3::Zero(), c1 = Vec3::Zero(), c2 = Vec3::Zero();
  switch (pair.kind) {
    case PrimitiveKind::kPointPlane: {
      // the plane's world normal and offset (its map is a rigid motion)
      X1 = g1.points[pair.ia];
      c1 = world1(pair.ia);
      const Vec3 n_W = (A2 * g2.plane_normal).normalized();
      const double offset_W = g2.plane_offset + n_W.dot(p2);
      const double s = n_W.dot(c1) - offset_W;
      c2 = c1 - s * n_W;
      X2 = A2.inverse() * (c2 - p2);
      out.d = s - g1.radius;
      const Vec3 n12 = -n_W;  // from the point towards the solid below the plane
      out.n = swapped ? -n12 : n12;
      out.Xa = swapped ? X2 : X1;
      out.Xb = swapped ? X1 : X2;
      out.is_signed = true;
      return out;
    }
    case PrimitiveKind::kPointTriangle: {
      const auto& t = g2.triangles[pair.ib];
      c1 = world1(pair.ia);
      const TriangleGap g = PointTriangleGap(c1, world2(t[0]), world2(t[1]), world2(t[2]), signed_depth);
      c2 = g.c;
      X1 = g1.points[pair.ia];
      X2 = g.w(0) * g2.points[t[0]] + g.w(1) * g2.points[t[1]] + g.w(2) * g2.points[t[2]];
      if (g.is_signed) {
        PairDistance signed_out = OrientPair(g.s - g1.radius - g2.radius, -g.n_out, X1, X2, swapped);
        signed_out.is_signed = true;
        return signed_out;
      }
      break;
    }
    case PrimitiveKind::kEdgeEdge: {
      const auto& e = g1.edges[pair.ia];
      const auto& f = g2.edges[pair.ib];
      const EdgeGap g = EdgeEdgeGap(world1(e[0]), world1(e[1]), world2(f[0]), world2(f[1]), p2 - p1, signed_depth);
      c1 = g.c1;
      c2 = g.c2;
      X1 = (1 - g.s1) * g1.points[e[0]] + g.s1 * g1.points[e[1]];
      X2 = (1 - g.s2) * g2.points[f[0]] + g.s2 * g2.points[f[1]];
      if (g.is_signed) {
        PairDistance signed_out = OrientPair(g.s - g1.radius - g2.radius, g.n, X1, X2, false);
        signed_out.is_signed = true;
        return signed_out;
      }
      break;
    }
    case PrimitiveKind::kPointSurface:
    case PrimitiveKind::kEdgeSurface:
    case PrimitiveKind::kTriangleSurface:
      return EvaluateSurfacePair(g1, p1, A1, g2, p2, A2, pair, signed_depth, barrier);
    case PrimitiveKind::kPointEdge: {
      const auto& e = g2.edges[pair.ib];
      double t = 0.0;
      c1 = world1(pair.ia);
      c2 = ClosestPointOnSegment(c1, world2(e[0]), world2(e[1]), &t);
      X1 = g1.points[pair.ia];
      X2 = (1 - t) * g2.points[e[0]] + t * g2.points[e[1]];
      break;
    }
    case PrimitiveKind::kPointPoint:
      X1 = g1.points[pair.ia];
      X2 = g2.points[pair.ib];
      c1 = world1(pair.ia);
      c2 = world2(pair.ib);
      break;
  }
  const Vec3 gap = c2 - c1;
  const double len = gap.norm();
  // touching (no direction between the closest points): from centre to centre
  const Vec3 centres = p2 - p1;
  const Vec3 n12 = len > 0.0 ? Vec3(gap / len) : centres.norm() > 0.0 ? Vec3(centres.normalized()) : Vec3::UnitZ();
  return OrientPair(len - g1.radius - g2.radius, n12, X1, X2, swapped);
}

}  // namespace contactsim
