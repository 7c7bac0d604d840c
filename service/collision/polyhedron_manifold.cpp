// Face clipping and edge-edge contacts of two polyhedra (see polyhedron_manifold.h).
#include "service/collision/polyhedron_manifold.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "service/collision/closest_points.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/feature_id.h"
#include "service/collision/manifold_reduction.h"

namespace contactsim {
namespace {

// Tags of the feature-id hash, so that ids of different kinds never mix.
constexpr uint32_t kTagClip = 0xC11Fu;
constexpr uint32_t kTagFace = 0xFACEu;
constexpr uint32_t kTagEdge = 0xED6Eu;
constexpr uint32_t kTagFallback = 0xFA11u;

// Depths (m) closer than this are the same (round-off of ~1 m coordinates).
constexpr double kDepthTol = 1e-9;

// p is inside the polyhedron or within kDepthTol of its surface.
bool InsidePolyhedron(const PosedPolyhedron& poly, const Vec3& p) {
  for (size_t f = 0; f < poly.normals.size(); ++f) {
    if (poly.normals[f].dot(p) - poly.offsets[f] > kDepthTol) return false;
  }
  return true;
}

// Sutherland-Hodgman: keeps the part of `poly` with n.p <= offset. A point
// within kDepthTol of the plane is on it: two flush faces of equal boxes
// have edges on each other's side planes, each end a round-off either side,
// and cutting such an edge put a point anywhere along it (t = dp / (dp - dq)
// of two ~1e-17 distances). In an aligned stack that point replaced a
// corner of the manifold and the stack leaned.
void ClipAgainstPlane(const std::vector<ClipPoint>& poly, const Vec3& n, double offset, uint32_t plane,
                      std::vector<ClipPoint>* out) {
  out->clear();
  const size_t m = poly.size();
  for (size_t k = 0; k < m; ++k) {
    const ClipPoint& p = poly[k];
    const ClipPoint& q = poly[k + 1 == m ? 0 : k + 1];  // no division in the loop
    const double dp = n.dot(p.p) - offset;
    const double dq = n.dot(q.p) - offset;
    const bool p_in = dp <= kDepthTol, q_in = dq <= kDepthTol;
    if (p_in) out->push_back(p);
    if (p_in != q_in) {
      const double t = std::clamp(dp / (dp - dq), 0.0, 1.0);
      out->push_back({p.p + t * (q.p - p.p), FeatureId({kTagClip, plane, p.tag, q.tag})});
    }
  }
}

void FaceManifold(const PosedPolyhedron& a, const PosedPolyhedron& b, const SatResult& sat,
                  double margin, ContactSet* out, ClipBuffers* buffers) {
  const bool ref_is_a = sat.axis.kind == SeparatingAxis::Kind::kFaceA;
  const PosedPolyhedron& ref = ref_is_a ? a : b;
  const PosedPolyhedron& inc = ref_is_a ? b : a;
  const int ref_face = ref_is_a ? sat.axis.a : sat.axis.b;
  const Vec3& n_ref = ref.normals[ref_face];
  const double ref_offset = ref.offsets[ref_face];
  const Vec3 normal_ab = ref_is_a ? n_ref : Vec3(-n_ref);

  // incident face: most anti-parallel to the reference normal
  int inc_face = 0;
  double min_dot = std::numeric_limits<double>::infinity();
  for (int g = 0; g < static_cast<int>(inc.normals.size()); ++g) {
    const double d = inc.normals[g].dot(n_ref);
    if (d < min_dot) {
      min_dot = d;
      inc_face = g;
    }
  }

  std::vector<ClipPoint>& poly = buffers->poly;
  std::vector<ClipPoint>& clipped = buffers->clipped;
  poly.clear();
  for (int v : inc.topology->faces[inc_face].vertices) {
    poly.push_back({inc.vertices[v], static_cast<uint32_t>(v)});
  }
  // side planes of the reference face: edge x normal points out of the face
  // for a counter-clockwise loop seen from outside
  const std::vector<int>& loop = ref.topology->faces[ref_face].vertices;
  for (size_t j = 0; j < loop.size() && !poly.empty(); ++j) {
    const Vec3& p0 = ref.vertices[loop[j]];
    const Vec3& p1 = ref.vertices[loop[j + 1 == loop.size() ? 0 : j + 1]];
    const Vec3 side = (p1 - p0).cross(n_ref);
    const double len = side.norm();
    if (len <= 0.0) continue;
    const Vec3 side_n = side / len;
    ClipAgainstPlane(poly, side_n, side_n.dot(p0), static_cast<uint32_t>(j), &clipped);
    poly.swap(clipped);
  }

  const uint32_t ref_side = ref_is_a ? 0u : 1u;
  const size_t first = out->size();
  double deepest = -std::numeric_limits<double>::infinity();
  for (const ClipPoint& cp : poly) {
    const double s = n_ref.dot(cp.p) - ref_offset;  // < 0 below the reference face
    if (-s <= -margin) continue;
    // cp.p is on the incident surface; the reference surface is -s n_ref away
    const Vec3 surface_a = ref_is_a ? Vec3(cp.p - s * n_ref) : cp.p;
    AppendContact(surface_a, normal_ab, -s,
                  FeatureId({kTagFace, ref_side, static_cast<uint32_t>(ref_face),
                             static_cast<uint32_t>(inc_face), cp.tag}),
                  out);
    deepest = std::max(deepest, -s);
  }
  if (deepest < -sat.separation - kDepthTol) {
    // the incident body's deepest vertex, which defines the axis's depth, is
    // off the incident face or outside the reference face's side planes
    // (deep overlaps of hulls; or round-off left no point): add it, so that
    // the deepest contact has the axis's depth and a penetrating pair is not
    // lost. Only where it is inside the reference body: the far end of a
    // long plank tilted over a short support lies below the support's top
    // plane but beside the support, where it touches nothing, and a point
    // there gave the support a lever arm of the plank's length
    // (docs/physics.md, "Manifold points beside the body").
    const int v = SupportVertex(inc, -n_ref);
    const double s = n_ref.dot(inc.vertices[v]) - ref_offset;
    const bool none = out->size() == first;
    if (-s > -margin && (none || InsidePolyhedron(ref, inc.vertices[v]))) {
      const Vec3 surface_a = ref_is_a ? Vec3(inc.vertices[v] - s * n_ref) : inc.vertices[v];
      AppendContact(surface_a, normal_ab, -s,
                    FeatureId({kTagFallback, ref_side, static_cast<uint32_t>(ref_face),
                               static_cast<uint32_t>(v)}),
                    out);
    }
  }
  ReduceManifold(first, out);
}

void EdgeManifold(const PosedPolyhedron& a, const PosedPolyhedron& b, const SatResult& sat,
                  double margin, ContactSet* out) {
  const double depth = -sat.separation;
  if (depth <= -margin) return;
  // the SAT keeps only Minkowski-face edge pairs, which are the touching edges
  const int ea = sat.axis.a;
  const int eb = sat.axis.b;
  const auto& edge_a = a.topology->edges[ea];
  const auto& edge_b = b.topology->edges[eb];
  const SegmentClosestPoints cp = ClosestPointsOfSegments(a.vertices[edge_a[0]], a.vertices[edge_a[1]],
                                                          b.vertices[edge_b[0]], b.vertices[edge_b[1]]);
  // the closest points are the two surface points; the SAT separation is
  // their distance along the axis
  const Vec3 mid = 0.5 * (cp.c1 + cp.c2);
  AppendContact(mid + 0.5 * depth * sat.normal, sat.normal, depth,
                FeatureId({kTagEdge, static_cast<uint32_t>(ea), static_cast<uint32_t>(eb)}), out);
}

}  // namespace

void PolyhedronManifold(const PosedPolyhedron& a, const PosedPolyhedron& b, const SatResult& sat,
                        double margin, ContactSet* out, ClipBuffers* buffers) {
  if (sat.axis.kind == SeparatingAxis::Kind::kEdges) {
    EdgeManifold(a, b, sat, margin, out);
  } else if (sat.axis.kind != SeparatingAxis::Kind::kNone) {
    FaceManifold(a, b, sat, margin, out, buffers);
  }
}

}  // namespace contactsim
