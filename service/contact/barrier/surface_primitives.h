// The barrier method's distances against a static triangle mesh or
// heightfield (triangle_surface.h).
//
// IPC sums a barrier over every primitive pair within d_hat (Li et al.
// 2020, sec. 4). Against a tessellated surface that sum counts the
// tessellation: a point at height h over a flat floor, a distance s from a
// shared edge, is within d_hat of both triangles, and the second one's pair
// (distance sqrt(h^2 + s^2), to the shared edge) pushes it up and away from
// the edge: a ridge of height b(h) along every edge of a flat floor, the
// barrier's ghost edge. Each point, edge and triangle of a body is
// therefore paired with the surface as a whole, at its distance to the
// nearest triangle (a point), convex edge (an edge) or vertex with a convex
// edge (a triangle) of the surface: over a flat floor a point's distance
// is its height, with the floor's normal, wherever it is. The free space
// next to a flat or concave edge or vertex is locally convex (the
// intersection of its faces' half-spaces), so a body reaches such an edge
// or vertex only after its own vertices reach the faces: counting them
// only adds the floor's vertices ahead of a sliding box, whose distance to
// its front face's bottom edge, sqrt(h^2 + s^2) at height h, pushed it
// back at every vertex (a 1 kg box launched at 4 m/s over the 0.1 m grid
// was thrown into a tumble in its first step). Edges convex beyond
// round-off (SurfaceTriangle::convex_edges, kConvexEdgeAngle) and open
// edges count. Together the three give the exact distance of a disjoint
// body and the surface, as IPC's point-triangle and edge-edge pairs do for
// two bodies. An edge pair takes the surface edge of
// the largest mollified barrier m b (edge_mollifier.h), so a body's edge
// lying along a surface edge is carried by the crossing edges and points
// at the same distance, as IPC's mollifier intends, and the pair's energy
// is the largest of its candidates' (continuous as they change).
//
// The surface's triangles near the primitive come from its box tree (a
// mesh) or its grid (a heightfield) through ForEachSurfaceTriangle, over
// the primitive's box grown by the surface's reach (its SurfaceGeometry):
// a distance below the reach is exact, and one beyond is reported as the
// reach, a lower bound, which keeps the additive CCD (additive_ccd.h) safe.
// The surface is static: its side of a pair has no vertices that move.
//
// CCD over a flat part of the surface: conservative advancement with the
// primitive's whole motion as its bound (additive_ccd.h) cuts a body
// sliding at 4 m/s, 17 mm a step, resting 10 um above a floor to some
// 32 x 9 um of its step. Where every triangle within the reach of the
// primitive's path lies in one plane, the surface within reach is that
// plane, and the distance is at least the smallest signed distance of the
// primitive's vertices to it (exact for a point over a face, and for an
// edge or face parallel to it), which is linear in alpha along each
// vertex's path: the first alpha at which a vertex reaches the target is
// safe, as for a plane body.
#pragma once

#include "service/contact/barrier/affine_body.h"
#include "service/contact/barrier/contact_primitives.h"

namespace contactsim {

// EvaluatePair for the kinds kPointSurface, kEdgeSurface and
// kTriangleSurface: g1 the body whose primitive is paired (at p1, A1), g2
// the surface (at p2, A2, a rigid map); `swapped` in the pair when g1 is b.
PairDistance EvaluateSurfacePair(const BodyGeometry& g1, const Vec3& p1, const Mat3& A1, const BodyGeometry& g2,
                                 const Vec3& p2, const Mat3& A2, const PrimitivePair& pair, double signed_depth,
                                 const PairBarrier& barrier);

// The largest alpha in [0, limit] for which the pair's distance stays at or
// above `target` (m) when body g1 moves from q1 by alpha dq1, by the plane
// bound above; false when the surface near the path is not flat (or a
// vertex starts below the target), for the caller's general bound.
bool FlatSurfaceCcd(const BodyGeometry& g1, const Vec12& q1, const Vec12& dq1, const BodyGeometry& g2,
                    const Vec12& q2, const PrimitivePair& pair, double target, double limit, double* alpha);

}  // namespace contactsim
