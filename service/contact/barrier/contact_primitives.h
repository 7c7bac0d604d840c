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
// minus the two radii. For polyhedra these pairs give the exact distance of
// two disjoint bodies (IPC's point-triangle and edge-edge constraints).
#pragma once

#include <array>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/shape.h"

namespace contactsim {

struct BodyGeometry {
  std::vector<Vec3> points;                 // m, body frame
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> triangles;
  double radius = 0.0;                      // m, sphere and capsule
  bool plane = false;                       // half-space {n . X <= offset}, body frame
  Vec3 plane_normal = Vec3::UnitZ();
  double plane_offset = 0.0;
};

BodyGeometry MakeBodyGeometry(const Shape& shape);

enum class PrimitiveKind { kPointTriangle, kEdgeEdge, kPointEdge, kPointPoint, kPointPlane };

// A pair of primitives of bodies a and b; for the point kinds the point
// belongs to `a` unless `swapped` (then the point is b's and the other
// primitive a's).
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
};
PairDistance EvaluatePair(const BodyGeometry& a, const Vec3& pa, const Mat3& Aa, const BodyGeometry& b,
                          const Vec3& pb, const Mat3& Ab, const PrimitivePair& pair, double signed_depth = 0.0);

}  // namespace contactsim
