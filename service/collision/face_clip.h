// Clipping an incident polygon to a reference face, the steps of a face
// contact that the general polyhedron manifold (polyhedron_manifold.h) and
// the box-box one (box_box_manifold.h) share, so that both make the same
// points, depths and feature ids bit for bit. (Ericson, "Real-Time Collision
// Detection", 8.3.4; Gregorius, "Robust Contact Creation for Physics
// Simulations", GDC 2015.)
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "service/collision/clip_buffers.h"
#include "service/collision/contact.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/feature_id.h"

namespace contactsim {

// Tags of the feature-id hash, so that ids of different kinds never mix.
constexpr uint32_t kTagClip = 0xC11Fu;
constexpr uint32_t kTagFace = 0xFACEu;
constexpr uint32_t kTagEdge = 0xED6Eu;
constexpr uint32_t kTagFallback = 0xFA11u;

// Depths (m) closer than this are the same (round-off of ~1 m coordinates).
constexpr double kClipDepthTol = 1e-9;

// A polygon of at most N points on the stack, for faces of known size: one
// clip at most doubles a polygon (each input point gives itself and at most
// one crossing), so a quad clipped by a quad's four side planes stays
// within 4 * 2^4 = 64.
template <size_t N>
class FixedClipPolygon {
 public:
  void clear() { size_ = 0; }
  void push_back(const ClipPoint& p) { points_[size_++] = p; }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const ClipPoint& operator[](size_t i) const { return points_[i]; }
  const ClipPoint* data() const { return points_.data(); }

 private:
  std::array<ClipPoint, N> points_;
  size_t size_ = 0;
};

// The reference face of a face contact in the world frame.
struct ReferenceFace {
  Vec3 normal;             // unit, outward of the reference body
  double offset = 0.0;     // m: normal . p = offset on the face
  Vec3 normal_ab;          // the contact normal, from A to B
  bool ref_is_a = true;    // the reference face is A's
  int index = -1;          // the reference face's index in its topology
};

// Sutherland-Hodgman: keeps the part of `poly` with n.p <= offset. A point
// within kClipDepthTol of the plane is on it: two flush faces of equal
// boxes have edges on each other's side planes, each end a round-off
// either side, and cutting such an edge put a point anywhere along it
// (t = dp / (dp - dq) of two ~1e-17 distances). In an aligned stack that
// point replaced a corner of the manifold and the stack leaned.
template <class Polygon>
void ClipAgainstPlane(const Polygon& poly, const Vec3& n, double offset, uint32_t plane, Polygon* out) {
  out->clear();
  const size_t m = poly.size();
  if (m == 0) return;
  // each point's distance once: as the edge's end it is the next edge's start
  const double d0 = n.dot(poly[0].p) - offset;
  double dp = d0;
  for (size_t k = 0; k < m; ++k) {
    const ClipPoint& p = poly[k];
    const ClipPoint& q = poly[k + 1 == m ? 0 : k + 1];  // no division in the loop
    const double dq = k + 1 == m ? d0 : n.dot(q.p) - offset;
    const bool p_in = dp <= kClipDepthTol, q_in = dq <= kClipDepthTol;
    if (p_in) out->push_back(p);
    if (p_in != q_in) {
      const double t = std::clamp(dp / (dp - dq), 0.0, 1.0);
      out->push_back({p.p + t * (q.p - p.p), FeatureId({kTagClip, plane, p.tag, q.tag})});
    }
    dp = dq;
  }
}

// Clips `poly` against the side planes of the reference face whose vertex
// loop (world, counter-clockwise seen from outside) is loop(0), ...,
// loop(count - 1): edge x normal points out of the face. The two polygons
// take turns as input and output; returns the one holding the result.
template <class Polygon, class Loop>
Polygon* ClipToReferenceFace(const Loop& loop, size_t count, const Vec3& n_ref, Polygon* poly, Polygon* scratch) {
  for (size_t j = 0; j < count && !poly->empty(); ++j) {
    const Vec3& p0 = loop(j);
    const Vec3& p1 = loop(j + 1 == count ? 0 : j + 1);
    const Vec3 side = (p1 - p0).cross(n_ref);
    const double len = side.norm();
    if (len <= 0.0) continue;
    const Vec3 side_n = side / len;
    ClipAgainstPlane(*poly, side_n, side_n.dot(p0), static_cast<uint32_t>(j), scratch);
    std::swap(poly, scratch);
  }
  return poly;
}

// Appends the points of the clipped polygon closer to the reference plane
// than the margin, each on the incident surface moved to midway between the
// surfaces, with the feature id of the two faces and the point's tag.
// Returns the deepest depth appended (-inf when none).
double AppendFacePoints(const ReferenceFace& ref, int inc_face, const ClipPoint* poly, size_t count, double margin,
                        ContactSet* out);

// Clipping lost the axis's depth (m): the deepest point appended lies
// shallower than the separating axis says the bodies overlap.
inline bool ClippingLostTheDepth(double deepest, double axis_depth) { return deepest < axis_depth - kClipDepthTol; }

// Appends the incident body's deepest vertex along -face.normal as one more
// contact, when ClippingLostTheDepth: that vertex, which defines the axis's
// depth, is off the incident face or outside the reference face's side
// planes (deep overlaps of hulls; or round-off left no point), and adding
// it gives the deepest contact the axis's depth and keeps a penetrating
// pair from being lost. Only where it is inside the reference body (or the
// contacts from `first` on are none): the far end of a long plank tilted
// over a short support lies below the support's top plane but beside the
// support, where it touches nothing, and a point there gave the support a
// lever arm of the plank's length (docs/physics.md, "Manifold points beside
// the body"). inc_vertex(v) is the incident body's vertex v of `count`
// (the first of the largest projection wins, as SupportVertex), and
// inside_ref(p) whether p is inside the reference body or within
// kClipDepthTol of its surface.
template <class IncVertex, class InsideRef>
void AppendDeepestIncidentVertex(int count, const IncVertex& inc_vertex, const InsideRef& inside_ref,
                                 const ReferenceFace& face, size_t first, double margin, ContactSet* out) {
  const Vec3& n_ref = face.normal;
  const Vec3 down = -n_ref;
  int v = 0;
  double best = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double p = down.dot(inc_vertex(i));
    if (p > best) {
      best = p;
      v = i;
    }
  }
  const Vec3 vertex = inc_vertex(v);
  const double s = n_ref.dot(vertex) - face.offset;
  const bool none = out->size() == first;
  if (-s > -margin && (none || inside_ref(vertex))) {
    const Vec3 surface_a = face.ref_is_a ? Vec3(vertex - s * n_ref) : vertex;
    AppendContact(surface_a, face.normal_ab, -s,
                  FeatureId({kTagFallback, face.ref_is_a ? 0u : 1u, static_cast<uint32_t>(face.index),
                             static_cast<uint32_t>(v)}),
                  out);
  }
}

}  // namespace contactsim
