// capsule-box and capsule-convex. The capsule A is the segment S = [p0, p1]
// grown by its radius r, so for a polyhedron B
//   depth = r - sd(S, B),
// with sd the signed distance of the segment: the Euclidean distance when S
// and B are apart, minus the translational penetration depth of S into B when
// they overlap (the support function of A is that of S plus r in every
// direction, so the overlap of A and B along any axis is that of S plus r).
//
// Overlap: S - B is a polytope whose faces are the faces of B and, for each
// edge of B on the silhouette seen along the segment (its two faces' normals
// on opposite sides of the segment's direction d), the parallelogram spanned
// by the edge and S, with normal d x e. Their largest separation is exactly
// minus the penetration depth (the separating-axis test of polyhedron_sat.h
// with a segment for A; Gregorius, "The Separating Axis Test between Convex
// Polyhedra", GDC 2013).
// Apart: the distance of a point to a convex set is a convex function of the
// point, so golden-section search along S finds the closest points.
//
// Contacts: when the normal is a face normal of B (the capsule lies on or in a
// face), the segment is clipped against the face's side planes and each end
// of the clipped part is a contact (two points: a capsule lying on a face does
// not roll about one point); otherwise (an edge or vertex of B) one contact at
// the closest points. The deepest contact always has the exact depth.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "service/collision/closest_points.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/feature_id.h"
#include "service/collision/polyhedron_distance.h"
#include "service/collision/polyhedron_sat.h"

namespace contactsim {
namespace {

// Segments shorter than this (m) are a point (a capsule of half length 0).
constexpr double kPointLength = 1e-12;
// A clipped part shorter than this (m) gives one contact, not two.
constexpr double kDistinctClipLength = 1e-6;
// The normal of a closest point is a face's normal when they agree to this
// (1 - cos): the closest point then lies inside the face and the normal is the
// face normal to round-off; at an edge or vertex it is strictly between.
constexpr double kFaceCos = 1e-9;
// Depths (m) closer than this are the same (round-off of ~1 m coordinates).
constexpr double kSameDepthTol = 1e-9;
// Golden-section iterations on [0, 1]: 0.618^80 ~ 2e-17 of the axis length.
constexpr int kGoldenIterations = 80;

// Tags of the feature-id hash, so that ids of different kinds never mix.
constexpr uint32_t kCapsuleTagFace = 0xCAFAu;
constexpr uint32_t kCapsuleTagEdge = 0xCAEDu;
constexpr uint32_t kCapsuleTagPoint = 0xCA90u;

// Minimiser of a convex function on [0, 1] by golden-section search.
double MinimiseConvex(const std::function<double(double)>& f) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = 0.0, hi = 1.0;
  double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < kGoldenIterations && hi - lo > 1e-15; ++i) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = f(x2);
    }
  }
  return 0.5 * (lo + hi);
}

// The axis of largest separation of segment S (A) and polyhedron B.
struct SegmentAxis {
  double separation = -std::numeric_limits<double>::infinity();  // m, > 0 apart
  Vec3 normal = Vec3::UnitZ();                                   // unit, from A to B
  int face = -1;                                                 // face of B, or
  int edge = -1;                                                 // edge of B
};

SegmentAxis SegmentSeparatingAxis(const Vec3& p0, const Vec3& p1, const PosedPolyhedron& b) {
  SegmentAxis best;
  // faces of B: S in front of face f by min over S of n_f.p - o_f
  for (int f = 0; f < static_cast<int>(b.normals.size()); ++f) {
    const Vec3& n = b.normals[f];
    const double sep = std::min(n.dot(p0), n.dot(p1)) - b.offsets[f];
    if (sep > best.separation) best = {sep, -n, f, -1};
  }
  const Vec3 d = p1 - p0;
  const double length = d.norm();
  if (length < kPointLength) return best;
  const Vec3 dir = d / length;
  for (int e = 0; e < static_cast<int>(b.edge_dirs.size()); ++e) {
    const Vec3 c = dir.cross(b.edge_dirs[e]);
    const double len = c.norm();
    if (len < kSatParallelSin) continue;  // parallel: the edge's faces separate
    Vec3 w = c / len;  // outward normal of B at the edge, along which S is
    const Vec3& pe = b.vertices[b.topology->edges[e][0]];
    double sep;
    if (const std::array<int, 2>* faces = EdgeFaces(b, e)) {
      // a face of S - B only for silhouette edges; w then lies on the edge's
      // Gauss-map arc, between its two face normals
      const Vec3& na = b.normals[(*faces)[0]];
      const Vec3& nb = b.normals[(*faces)[1]];
      if (dir.dot(na) * dir.dot(nb) >= 0.0) continue;
      if (w.dot(na + nb) < 0.0) w = -w;
      // B's support along w is the edge, every point of S projects alike
      sep = w.dot(p0 - pe);
    } else {
      // open topology: project B both ways
      double lo, hi;
      ProjectPolyhedron(b, w, &lo, &hi);
      const double s = w.dot(p0);
      if (s - hi < lo - s) w = -w;
      sep = std::max(s - hi, lo - s);
    }
    if (sep > best.separation) best = {sep, -w, -1, e};
  }
  return best;
}

// Both ends of S clipped to the prism over face f of B (Sutherland-Hodgman on
// a segment: the parameter interval inside every side plane); false when
// nothing of S is over the face. An end within kSameDepthTol of a side plane is on
// it, as in the polygon clip (polyhedron_manifold.cpp): a capsule lying along
// a face's edge has both ends in that side plane up to round-off, and cutting
// it there would put its contact at an arbitrary point of the axis.
bool ClipSegmentToFace(const Vec3& p0, const Vec3& p1, const PosedPolyhedron& b, int f, double* t0,
                       double* t1) {
  const Vec3& n = b.normals[f];
  double lo = 0.0, hi = 1.0;
  const std::vector<int>& loop = b.topology->faces[f].vertices;
  for (size_t j = 0; j < loop.size(); ++j) {
    const Vec3& v0 = b.vertices[loop[j]];
    const Vec3& v1 = b.vertices[loop[(j + 1) % loop.size()]];
    // edge x normal points out of a counter-clockwise face
    const Vec3 side = (v1 - v0).cross(n).normalized();
    const double d0 = side.dot(p0 - v0), d1 = side.dot(p1 - v0);  // m, <= 0 inside
    const bool in0 = d0 <= kSameDepthTol, in1 = d1 <= kSameDepthTol;
    if (!in0 && !in1) return false;
    if (in0 == in1) continue;
    const double t = std::clamp(d0 / (d0 - d1), 0.0, 1.0);
    if (in0) {
      hi = std::min(hi, t);
    } else {
      lo = std::max(lo, t);
    }
  }
  if (lo > hi) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

}  // namespace

double AppendCapsuleFaceContacts(const Vec3& p0, const Vec3& p1, double r, const PosedPolyhedron& b, int f,
                                 double margin, ContactSet* out) {
  double t0, t1;
  double deepest = -std::numeric_limits<double>::infinity();
  if (!ClipSegmentToFace(p0, p1, b, f, &t0, &t1)) return deepest;
  const Vec3& n = b.normals[f];
  const bool single = (t1 - t0) * (p1 - p0).norm() < kDistinctClipLength;
  const double ends[2] = {t0, t1};
  for (int k = 0; k < (single ? 1 : 2); ++k) {
    const Vec3 c = p0 + ends[k] * (p1 - p0);
    const double height = n.dot(c) - b.offsets[f];
    if (r - height <= -margin) continue;
    AppendSphereContact(c, r, height, n, FeatureId({kCapsuleTagFace, static_cast<uint32_t>(f), static_cast<uint32_t>(k)}),
                         margin, out);
    deepest = std::max(deepest, r - height);
  }
  return deepest;
}

void CollideCapsulePolyhedron(const RigidBody& a, const RigidBody& b, const CollideContext& ctx,
                              ContactSet* out) {
  PosedPolyhedron poly;
  if (!PosePolyhedron(b, &poly)) return;
  Vec3 p0, p1;
  CapsuleSegment(a, &p0, &p1);
  CollideSegmentPolyhedron(p0, p1, a.shape.radius, poly, b.shape.type == ShapeType::kBox ? &b : nullptr,
                           ctx.margin, out);
}

void CollideSegmentPolyhedron(const Vec3& p0, const Vec3& p1, double r, const PosedPolyhedron& poly,
                              const RigidBody* box, double margin, ContactSet* out) {
  const SegmentAxis axis = SegmentSeparatingAxis(p0, p1, poly);
  // the separation of an axis is a lower bound of the distance
  if (r - axis.separation <= -margin) return;
  // the exact contact: a point c of S, its signed distance to B and the unit
  // normal m out of B there; the face of B that m is the normal of, if any
  Vec3 c;
  double distance;
  Vec3 m;
  int face = -1;
  uint32_t id;
  if (axis.separation <= 0.0) {
    distance = axis.separation;
    m = -axis.normal;
    if (axis.face >= 0) {
      // the deepest point of S along the face normal
      face = axis.face;
      c = m.dot(p0) <= m.dot(p1) ? p0 : p1;
      id = FeatureId({kCapsuleTagFace, static_cast<uint32_t>(face), 2u});
    } else {
      const auto& e = poly.topology->edges[axis.edge];
      c = ClosestPointsOfSegments(p0, p1, poly.vertices[e[0]], poly.vertices[e[1]]).c1;
      id = FeatureId({kCapsuleTagEdge, static_cast<uint32_t>(axis.edge)});
    }
  } else {
    const auto query = [&](const Vec3& p) {
      return box != nullptr ? BoxSignedDistance(*box, p) : PolyhedronSignedDistance(poly, p);
    };
    const double t = MinimiseConvex([&](double u) { return query(p0 + u * (p1 - p0)).distance; });
    c = p0 + t * (p1 - p0);
    const SurfaceQuery q = query(c);
    distance = q.distance;
    m = q.normal;
    id = FeatureId({kCapsuleTagPoint, static_cast<uint32_t>(q.feature)});
    int best = 0;
    for (int f = 1; f < static_cast<int>(poly.normals.size()); ++f) {
      if (poly.normals[f].dot(m) > poly.normals[best].dot(m)) best = f;
    }
    if (poly.normals[best].dot(m) >= 1.0 - kFaceCos) face = best;
  }
  const double depth = r - distance;
  if (depth <= -margin) return;

  double deepest = -std::numeric_limits<double>::infinity();
  if (face >= 0) deepest = AppendCapsuleFaceContacts(p0, p1, r, poly, face, margin, out);
  // the exact point, unless a face contact already has its depth (it can lie
  // outside the face when S pokes out of a side of B)
  if (deepest < depth - kSameDepthTol) AppendSphereContact(c, r, distance, m, id, margin, out);
}

}  // namespace contactsim
