// The triangles of a static surface (a triangle mesh or a heightfield), as
// the narrowphase and the ray cast take them, and the edge rule that keeps
// a body sliding over a flat or concave edge from seeing that edge.
//
// Ghost collisions: a body crossing the shared edge of two coplanar
// triangles overlaps the next triangle by a sliver, and that triangle on its
// own has its least penetration across the edge, so its contact normal
// points along the floor and the body catches on a seam that does not exist.
// Each triangle therefore records, per edge, whether the edge is *active*:
// convex with a dihedral angle above kActiveEdgeAngle (Jolt's active edges,
// MeshShape's `mActiveEdgeCosThresholdAngle`; Bullet's
// btAdjustInternalEdgeContacts does the same by correcting normals). A flat
// or concave edge, and a vertex both of whose edges in the triangle are
// inactive, never gives a normal: a contact on one takes the triangle's face
// normal instead (collide_surface.cpp). An open edge (one triangle) or a
// non-manifold one (three or more) is active.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "service/collision/aabb.h"
#include "service/collision/height_field.h"
#include "service/collision/surface_triangle.h"
#include "service/collision/triangle_mesh.h"
#include "service/physics/math.h"
#include "service/physics/shape.h"

namespace contactsim {

// Edges are active when convex by more than 5 degrees (Jolt's default
// threshold): a tessellated curve of finer facets is as smooth as its faces.
constexpr double kActiveEdgeAngle = 5.0 * M_PI / 180.0;  // rad

// Convex beyond round-off: the smallest dihedral turn that makes an edge
// convex for the barrier's distances (surface_triangle.h, convex_edges).
constexpr double kConvexEdgeAngle = 1e-6;  // rad

// Whether edge a -> b of a triangle with unit normal `n` is active, given
// the vertex `w` of the neighbour across it (the neighbour taken as wound
// consistently with this triangle, so that a file's inconsistent winding
// does not matter): convex (w below this triangle's plane) by more than
// `angle`.
bool EdgeIsActive(const Vec3& n, const Vec3& a, const Vec3& b, const Vec3& w, double angle = kActiveEdgeAngle);

// The triangle a, b, c with its unit normal; false when its area is zero
// (to round-off of its longest edge).
bool MakeSurfaceTriangle(const Vec3& a, const Vec3& b, const Vec3& c, SurfaceTriangle* tri);

// The box (body frame) that holds every triangle of a mesh or heightfield shape.
Aabb SurfaceBounds(const Shape& shape);

// Calls visit(const SurfaceTriangle&) for every triangle (body frame) of a
// mesh or heightfield shape whose box overlaps `box` (body frame).
template <class Visit>
void ForEachSurfaceTriangle(const Shape& shape, const Aabb& box, Visit&& visit);

// The box, in the frame of a body at rotation R and position x, that holds
// the world box `world`.
Aabb BoxInBodyFrame(const Aabb& world, const Mat3& R, const Vec3& x);

// The triangle moved to the world by the body's pose.
SurfaceTriangle TriangleInWorld(const SurfaceTriangle& tri, const Mat3& R, const Vec3& x);

template <class Visit>
void ForEachSurfaceTriangle(const Shape& shape, const Aabb& box, Visit&& visit) {
  if (shape.type == ShapeType::kMesh && shape.mesh != nullptr) {
    const TriangleMesh& mesh = *shape.mesh;
    mesh.tree.Overlap(box, [&](int t) {
      if (mesh.boxes[t].Overlaps(box)) visit(mesh.Triangle(t));
    });
  } else if (shape.type == ShapeType::kHeightfield && shape.heightfield != nullptr) {
    shape.heightfield->ForEachTriangle(box, visit);
  }
}

}  // namespace contactsim
