// sphere, box, capsule and convex hull against a triangle mesh or a
// heightfield (triangle_surface.h): the body's box, in the surface's frame,
// picks the triangles near it (the mesh's box tree, or the heightfield's
// cells), and each triangle is collided as a thin polyhedron, a prism under
// the triangle, by the pair code the body has against a hull (the
// separating-axis test and face clipping, the segment test of a capsule,
// the signed distance of a sphere's centre).
//
// Each triangle's contacts then pass the edge rule (triangle_surface.h):
// a contact whose normal is not the face normal lies on an edge or vertex
// of the triangle; if that feature is inactive (a flat or concave edge, a
// vertex with no active edge in the triangle), or the normal points behind
// the face, the triangle's contacts are made again with its face normal
// alone (Jolt's ActiveEdges::FixNormal, which also replaces such a normal
// with the triangle's). A face-normal contact of a sphere or capsule keeps
// only what lies over the triangle, and a polyhedron's is clipped to it, so
// the triangles of a flat floor tile the body's contact without overlap.
// Triangles are one-sided: a body whose centre is behind a triangle's
// plane does not touch it, so a body is never pushed through a surface.
//
// The contacts of all triangles are finally grouped by normal, duplicates
// (a point on a shared edge, found by both triangles) merged, and each group
// reduced to four points (manifold_reduction.h), as one face pair's would be.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "service/collision/aabb.h"
#include "service/collision/collide_pairs.h"
#include "service/collision/feature_id.h"
#include "service/collision/manifold_reduction.h"
#include "service/collision/polyhedron_distance.h"
#include "service/collision/polyhedron_manifold.h"
#include "service/collision/polyhedron_sat.h"
#include "service/collision/triangle_surface.h"

namespace contactsim {
namespace {

// A contact normal within this of the face normal (1 - cos, ~1.4e-6 rad)
// is the face normal, to round-off. Anything more tilted comes from an edge
// or vertex (a ball whose centre is 0.1 mm past an edge sees it 1e-3 rad
// tilted) and must pass the edge rule.
constexpr double kFaceNormalCos = 1e-12;
// A body's face within this of the triangle's (1 - cos, ~0.08 degrees)
// lies on it: the triangle is taken as the reference face.
constexpr double kParallelFaceCos = 1e-6;
// Normals of one manifold group agree to this (1 - cos): coplanar
// triangles' normals differ by round-off only. (Grouping within the
// active-edge angle instead, to give fewer points on curved surfaces, let
// a hull fall through a wavy heightfield under xpbd: a group's four points
// then need not hold each triangle's contact.)
constexpr double kSameNormalCos = 1e-9;
// Points of one group closer than this (m) are one point.
constexpr double kSamePoint = 1e-9;
// A point within this (m) of an edge's line, beyond the contact's depth,
// is on the edge: clipping and closest points put it there to round-off.
constexpr double kOnEdge = 1e-7;
constexpr uint32_t kTagSurface = 0x5EFAu;

// The prism under a triangle: vertices 0-2 the triangle, 3-5 the same
// pushed back along its normal; face 0 the triangle, 1 the back, 2 + k the
// side over edge k (vertex k to k + 1).
ConvexHull MakePrismTopology() {
  ConvexHull prism;
  prism.vertices.assign(6, Vec3::Zero());
  const int loops[5][4] = {{0, 1, 2, -1}, {3, 5, 4, -1}, {0, 3, 4, 1}, {1, 4, 5, 2}, {2, 5, 3, 0}};
  for (const auto& loop : loops) {
    ConvexHull::Face face;
    for (int v : loop) {
      if (v >= 0) face.vertices.push_back(v);
    }
    prism.faces.push_back(face);
  }
  prism.edges = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
  ConnectEdgeFaces(&prism);
  return prism;
}

const ConvexHull& PrismTopology() {
  static const ConvexHull kPrism = MakePrismTopology();
  return kPrism;
}

// Poses the prism of world triangle `tri`, as deep as its longest edge, so
// that a body penetrating less than that finds the triangle's face nearer
// than the back.
void PosePrism(const SurfaceTriangle& tri, PosedPolyhedron* out) {
  const Vec3& n = tri.normal;
  double depth = 0.0;
  for (int k = 0; k < 3; ++k) depth = std::max(depth, (tri.v[(k + 1) % 3] - tri.v[k]).norm());
  out->topology = &PrismTopology();
  out->vertices.resize(6);
  for (int k = 0; k < 3; ++k) {
    out->vertices[k] = tri.v[k];
    out->vertices[k + 3] = tri.v[k] - depth * n;
  }
  out->normals.resize(5);
  out->offsets.resize(5);
  out->normals[0] = n;
  out->offsets[0] = n.dot(tri.v[0]);
  out->normals[1] = -n;
  out->offsets[1] = -n.dot(out->vertices[3]);
  for (int k = 0; k < 3; ++k) {
    // edge x normal points out of a counter-clockwise face
    out->normals[2 + k] = (tri.v[(k + 1) % 3] - tri.v[k]).cross(n).normalized();
    out->offsets[2 + k] = out->normals[2 + k].dot(tri.v[k]);
  }
  const auto& edges = out->topology->edges;
  out->edge_dirs.resize(edges.size());
  for (size_t e = 0; e < edges.size(); ++e) {
    out->edge_dirs[e] = (out->vertices[edges[e][1]] - out->vertices[edges[e][0]]).normalized();
  }
  out->centre = (tri.v[0] + tri.v[1] + tri.v[2]) / 3.0 - 0.5 * depth * n;
}

// Whether a contact of normal `m` (out of the surface) at `point` may keep
// its normal: the face normal always; otherwise only in front of the face
// and on an active edge, or a vertex with an active edge.
bool KeepsNormal(const SurfaceTriangle& tri, const Vec3& m, const Vec3& point, double depth) {
  const double along = m.dot(tri.normal);
  if (along >= 1.0 - kFaceNormalCos) return true;
  if (along <= 0.0) return false;
  const double band = kOnEdge + std::max(depth, 0.0);
  for (int k = 0; k < 3; ++k) {
    const Vec3 edge = tri.v[(k + 1) % 3] - tri.v[k];
    const Vec3 inward = tri.normal.cross(edge).normalized();
    if (inward.dot(point - tri.v[k]) > band) continue;
    if (tri.active_edges & (1u << k)) return true;
  }
  // an inner point, or only inactive edges near it
  return false;
}

// The contacts of a piece (sphere, capsule, or the posed polyhedron `poly`
// of a box or hull) with the prism of `tri`, normals from the piece to the
// surface; `face_only` takes the triangle's face normal as the only axis.
void CollideTriangle(const RigidBody& a, const PosedPolyhedron* poly, const SurfaceTriangle& tri,
                     const PosedPolyhedron& prism, bool face_only, double margin, ClipBuffers* clip,
                     ContactSet* out) {
  const Vec3& n = tri.normal;
  const double offset = n.dot(tri.v[0]);
  switch (a.shape.type) {
    case ShapeType::kSphere: {
      if (!face_only) {
        const SurfaceQuery q = PolyhedronSignedDistance(prism, a.x);
        AppendSphereContact(a.x, a.shape.radius, q.distance, q.normal, 0, margin, out);
        return;
      }
      // the centre over the triangle: its height above the face
      for (int k = 0; k < 3; ++k) {
        if (prism.normals[2 + k].dot(a.x) - prism.offsets[2 + k] > 0.0) return;
      }
      AppendSphereContact(a.x, a.shape.radius, n.dot(a.x) - offset, n, 1, margin, out);
      return;
    }
    case ShapeType::kCapsule: {
      Vec3 p0, p1;
      CapsuleSegment(a, &p0, &p1);
      if (face_only) {
        AppendCapsuleFaceContacts(p0, p1, a.shape.radius, prism, 0, margin, out);
      } else {
        CollideSegmentPolyhedron(p0, p1, a.shape.radius, prism, nullptr, margin, out);
      }
      return;
    }
    case ShapeType::kBox:
    case ShapeType::kConvex: {
      SatResult sat;
      if (!face_only) {
        sat = FindSeparatingAxis(*poly, prism, margin);
        // a face of the body lying on the triangle: clip it to the triangle
        // instead, so that the triangles under a face tile it and give its
        // corners, as a plane does
        face_only = sat.axis.kind == SeparatingAxis::Kind::kFaceA && -sat.normal.dot(n) >= 1.0 - kParallelFaceCos;
      }
      if (face_only) {
        const SeparatingAxis axis{SeparatingAxis::Kind::kFaceB, -1, 0};
        Vec3 normal;
        double separation;
        if (!AxisSeparation(*poly, prism, axis, &normal, &separation)) return;
        sat = MakeSatResult(axis, normal, separation);
      }
      if (sat.separation > margin) return;
      PolyhedronManifold(*poly, prism, sat, margin, out, clip);
      return;
    }
    default: return;
  }
}

// Removes the contacts whose point lies outside the side planes of the
// triangle's prism. The face-normal test alone does not check that the body
// is over the triangle: a triangle beside the body (speculative, within the
// margin) that it lies below the plane of, uphill in a valley, left the
// manifold's fallback, the body's deepest vertex, as a contact centimetres
// deep where the body touched nothing, and penalty's springs sent a resting
// hull off at metres per second.
void DropPointsBesidePrism(const PosedPolyhedron& prism, ContactSet* found) {
  const auto beside = [&](const Contact& c) {
    for (int k = 0; k < 3; ++k) {
      if (prism.normals[2 + k].dot(c.point) - prism.offsets[2 + k] > kOnEdge) return true;
    }
    return false;
  };
  found->erase(std::remove_if(found->begin(), found->end(), beside), found->end());
}

// Appends `in` to `out` grouped by normal, each group without duplicate
// points and reduced to four.
void GroupAndReduce(ContactSet* in, ContactSet* out) {
  std::vector<bool> taken(in->size(), false);
  for (size_t i = 0; i < in->size(); ++i) {
    if (taken[i]) continue;
    const Vec3 n = (*in)[i].normal;
    const size_t first = out->size();
    for (size_t j = i; j < in->size(); ++j) {
      if (taken[j] || (*in)[j].normal.dot(n) < 1.0 - kSameNormalCos) continue;
      taken[j] = true;
      bool duplicate = false;
      for (size_t k = first; k < out->size() && !duplicate; ++k) {
        duplicate = ((*out)[k].point - (*in)[j].point).norm() < kSamePoint;
      }
      if (!duplicate) out->push_back((*in)[j]);
    }
    ReduceManifold(first, out);
  }
}

}  // namespace

void CollideSurface(const RigidBody& a, const RigidBody& b, const CollideContext& ctx, ContactSet* out) {
  PolyhedronScratch local;
  PolyhedronScratch& scratch = ctx.scratch != nullptr ? *ctx.scratch : local;
  const bool polyhedron = a.shape.type == ShapeType::kBox || a.shape.type == ShapeType::kConvex;
  if (polyhedron && !PosePolyhedron(a, &scratch.a)) return;
  const PosedPolyhedron* poly = polyhedron ? &scratch.a : nullptr;
  const Mat3 R = b.Rotation();
  ContactSet& all = scratch.surface;
  ContactSet& found = scratch.triangle;
  all.clear();
  ForEachSurfaceTriangle(b.shape, BoxInBodyFrame(ComputeAabb(a, ctx.margin, 0.0), b.Rotation(), b.x), [&](const SurfaceTriangle& local_tri) {
    const SurfaceTriangle tri = TriangleInWorld(local_tri, R, b.x);
    // one-sided: a body whose centre is behind the face does not touch it
    if (tri.normal.dot(a.x - tri.v[0]) < 0.0) return;
    PosePrism(tri, &scratch.b);
    found.clear();
    CollideTriangle(a, poly, tri, scratch.b, false, ctx.margin, &scratch.clip, &found);
    bool keep = true;
    for (const Contact& c : found) keep = keep && KeepsNormal(tri, -c.normal, c.point, c.depth);
    if (!keep) {
      found.clear();
      CollideTriangle(a, poly, tri, scratch.b, true, ctx.margin, &scratch.clip, &found);
      DropPointsBesidePrism(scratch.b, &found);
    }
    for (Contact& c : found) {
      c.feature_id = FeatureId({kTagSurface, tri.index, c.feature_id});
      all.push_back(c);
    }
  });
  GroupAndReduce(&all, out);
}

}  // namespace contactsim
