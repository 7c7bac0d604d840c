// The contact primitives of the barrier method (Li et al. 2020, "Incremental
// Potential Contact", sec. 4): every body is points, edges and triangles in
// its own frame (a sphere is a point and a capsule a segment, both with a
// radius offset; a plane is a static half-space), and the distance of two
// bodies is the smallest unsigned distance over
//   point-triangle pairs (the points of each against the other's triangles),
//   edge-edge pairs,
//   point-edge pairs against a body with edges but no triangles (capsule),
//   point-point pairs of two bodies with neither (spheres),
//   point-plane pairs,
//   against a static triangle mesh or heightfield, each point, edge and
//   triangle of the body paired with the surface as a whole
//   (surface_primitives.h),
// minus the two radii. For polyhedra these pairs give the exact distance of
// two disjoint bodies (IPC's point-triangle and edge-edge constraints).
#pragma once

#include <array>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/shape.h"

namespace contactsim {

// A static triangle mesh or heightfield (triangle_surface.h): its triangles
// are looked up near each primitive through the surface's own search
// structure, never listed (surface_primitives.h).
struct SurfaceGeometry {
  const Shape* shape = nullptr;  // kMesh or kHeightfield; null: not a surface
  double reach = 0.0;            // m, distances are exact below it and reported as it beyond
};

struct BodyGeometry {
  std::vector<Vec3> points;                 // m, body frame
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> triangles;
  double radius = 0.0;                      // m, sphere and capsule
  bool plane = false;                       // half-space {n . X <= offset}, body frame
  Vec3 plane_normal = Vec3::UnitZ();
  double plane_offset = 0.0;
  SurfaceGeometry surface;                  // a mesh or heightfield: no points, edges or triangles of its own
};

BodyGeometry MakeBodyGeometry(const Shape& shape);

// The last three pair a primitive of a body (point ia, edge ia, triangle
// ia) with a whole triangle surface: its nearest triangle, edge or vertex
// (surface_primitives.h).
enum class PrimitiveKind {
  kPointTriangle,
  kEdgeEdge,
  kPointEdge,
  kPointPoint,
  kPointPlane,
  kPointSurface,
  kEdgeSurface,
  kTriangleSurface
};

bool IsSurfaceKind(PrimitiveKind kind);

// A pair of primitives of bodies a and b; for the point kinds the point
// belongs to `a` unless `swapped` (then the point is b's and the other
// primitive a's); for the surface kinds the body's primitive is a's unless
// `swapped`, and ib is 0.
struct PrimitivePair {
  PrimitiveKind kind = PrimitiveKind::kPointPoint;
  int ia = 0, ib = 0;   // primitive indices on the point side / other side
  bool swapped = false;
};

// Every primitive pair of two bodies (one of them may be a plane).
void EnumeratePrimitivePairs(const BodyGeometry& a, const BodyGeometry& b, std::vector<PrimitivePair>* out);

// Up to four world points of each side of a pair (the primitive's vertices),
// body-frame coordinates; used for motion bounds.
struct PairVertices {
  std::array<Vec3, 3> a, b;
  int na = 0, nb = 0;
};
PairVertices PrimitiveVertices(const BodyGeometry& a, const BodyGeometry& b, const PrimitivePair& pair);

// Distance of a pair with the two bodies' world maps x = p + A X. Signed
// where the geometry gives a side: point-plane always; point-triangle when
// the point's foot on the triangle's plane lies in the triangle and the
// point is at most `signed_depth` behind it (the outward normal of the face
// is the direction); edge-edge when the closest points are inside both
// non-parallel edges and at most `signed_depth` past each other (e_a x e_b,
// turned from a's centre towards b's). So a pair measured from a shifted
// zero below d = 0 (barrier_solver.h) cannot pass through d = 0 unseen,
// and bodies placed exactly touching get the normal of the touching faces
// rather than none. Deeper, the distance is unsigned (a point far behind a
// face plane, as seen from a face on the other side of a body, is not
// inside). Elsewhere unsigned, with the normal from centre to centre when
// the closest points coincide.
struct PairDistance {
  double d = 0.0;         // m, distance minus radii
  Vec3 Xa, Xb;            // body-frame coordinates of the closest points
  Vec3 n = Vec3::UnitZ(); // unit, world, from a's closest point to b's
  bool is_signed = false; // by a side (plane, face, crossing edges), not |c_b - c_a|
  Vec3 surface_edge = Vec3::Zero();  // m, kEdgeSurface: the chosen surface edge (its body frame), for the mollifier
};
// `barrier` (kEdgeSurface only): the pair's barrier zero and width, by
// which the surface's edge is chosen (surface_primitives.h).
struct PairBarrier {
  double shift = 0.0;     // m, subtracted from the distance
  double width = 0.0;     // m, activation distance; 0: the nearest edge
};
PairDistance EvaluatePair(const BodyGeometry& a, const Vec3& pa, const Mat3& Aa, const BodyGeometry& b,
                          const Vec3& pb, const Mat3& Ab, const PrimitivePair& pair, double signed_depth = 0.0,
                          const PairBarrier& barrier = PairBarrier());

// The closest points of world point p and triangle (v0, v1, v2),
// counter-clockwise seen from its front: c with barycentric weights w; signed
// (s along the unit front normal n_out) when p's foot on the triangle's
// plane lies in the triangle and p is at most `signed_depth` behind it.
struct TriangleGap {
  Vec3 c, w, n_out;
  double s = 0.0;
  bool is_signed = false;
};
TriangleGap PointTriangleGap(const Vec3& p, const Vec3& v0, const Vec3& v1, const Vec3& v2, double signed_depth);

// The closest points of segments a0-a1 and b0-b1; signed (s along the unit
// n, e_a x e_b turned to `toward`, the direction from the first edge's body
// to the second's) when the edges cross with both closest points inside and
// at most `signed_depth` past each other.
struct EdgeGap {
  Vec3 c1, c2, n;
  double s1 = 0.0, s2 = 0.0;  // the closest points' parameters along a and b
  double s = 0.0;
  bool is_signed = false;
};
EdgeGap EdgeEdgeGap(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const Vec3& toward,
                    double signed_depth);

// A pair's distance d with n12 the unit normal from the body primitive's
// (side 1's) closest point X1 to side 2's X2, in a's and b's terms (side 1 is
// b when `swapped`).
PairDistance OrientPair(double d, const Vec3& n12, const Vec3& X1, const Vec3& X2, bool swapped);

}  // namespace contactsim
