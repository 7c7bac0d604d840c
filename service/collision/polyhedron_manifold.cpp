// Face clipping and edge-edge contacts of two polyhedra (see polyhedron_manifold.h).
#include "service/collision/polyhedron_manifold.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "service/collision/closest_points.h"
#include "service/collision/face_clip.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/feature_id.h"
#include "service/collision/manifold_reduction.h"

namespace contactsim {
namespace {

// p is inside the polyhedron or within kClipDepthTol of its surface.
bool InsidePolyhedron(const PosedPolyhedron& poly, const Vec3& p) {
  for (size_t f = 0; f < poly.normals.size(); ++f) {
    if (poly.normals[f].dot(p) - poly.offsets[f] > kClipDepthTol) return false;
  }
  return true;
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

  std::vector<ClipPoint>& incident = buffers->poly;
  incident.clear();
  for (int v : inc.topology->faces[inc_face].vertices) {
    incident.push_back({inc.vertices[v], static_cast<uint32_t>(v)});
  }
  const std::vector<int>& loop = ref.topology->faces[ref_face].vertices;
  const std::vector<ClipPoint>& poly = *ClipToReferenceFace(
      [&](size_t j) -> const Vec3& { return ref.vertices[loop[j]]; }, loop.size(), n_ref, &incident, &buffers->clipped);

  const ReferenceFace face{n_ref, ref_offset, normal_ab, ref_is_a, ref_face};
  const size_t first = out->size();
  const double deepest = AppendFacePoints(face, inc_face, poly.data(), poly.size(), margin, out);
  if (ClippingLostTheDepth(deepest, -sat.separation)) {
    AppendDeepestIncidentVertex(
        static_cast<int>(inc.vertices.size()), [&](int v) -> const Vec3& { return inc.vertices[v]; },
        [&](const Vec3& p) { return InsidePolyhedron(ref, p); }, face, first, margin, out);
  }
  ReduceManifold(first, out);
}

void EdgeManifold(const PosedPolyhedron& a, const PosedPolyhedron& b, const SatResult& sat,
                  double margin, ContactSet* out) {
  const auto& edge_a = a.topology->edges[sat.axis.a];
  const auto& edge_b = b.topology->edges[sat.axis.b];
  AppendEdgeContact(a.vertices[edge_a[0]], a.vertices[edge_a[1]], b.vertices[edge_b[0]], b.vertices[edge_b[1]], sat,
                    margin, out);
}

}  // namespace

void AppendEdgeContact(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const SatResult& sat,
                       double margin, ContactSet* out) {
  const double depth = -sat.separation;
  if (depth <= -margin) return;
  // the SAT keeps only Minkowski-face edge pairs, which are the touching edges
  const SegmentClosestPoints cp = ClosestPointsOfSegments(a0, a1, b0, b1);
  // the closest points are the two surface points; the SAT separation is
  // their distance along the axis
  const Vec3 mid = 0.5 * (cp.c1 + cp.c2);
  AppendContact(mid + 0.5 * depth * sat.normal, sat.normal, depth,
                FeatureId({kTagEdge, static_cast<uint32_t>(sat.axis.a), static_cast<uint32_t>(sat.axis.b)}), out);
}

void PolyhedronManifold(const PosedPolyhedron& a, const PosedPolyhedron& b, const SatResult& sat,
                        double margin, ContactSet* out, ClipBuffers* buffers) {
  if (sat.axis.kind == SeparatingAxis::Kind::kEdges) {
    EdgeManifold(a, b, sat, margin, out);
  } else if (sat.axis.kind != SeparatingAxis::Kind::kNone) {
    FaceManifold(a, b, sat, margin, out, buffers);
  }
}

}  // namespace contactsim
