// A box or convex hull placed in the world: world-frame vertices and face
// planes over a shared topology (face vertex loops and edges). A box is the
// unit cube's topology scaled by its half extents, so that one separating-axis
// test and one clipping routine serve boxes and hulls alike.
#pragma once

#include <array>
#include <vector>

#include "service/physics/convex_hull.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

struct PosedPolyhedron {
  const ConvexHull* topology = nullptr;  // face loops and edges (its geometry is not used)
  std::vector<Vec3> vertices;            // m, world
  std::vector<Vec3> normals;             // unit, world, outward, one per face
  std::vector<double> offsets;           // m: normals[f] . p = offsets[f] on face f
  std::vector<Vec3> edge_dirs;           // unit, world, one per topology edge
  Vec3 centre = Vec3::Zero();            // m, world (centre of mass)
};

// The two faces on edge e (ConvexHull::edge_faces), or nullptr when the
// topology lacks one of them (an open or hand-built topology), where edge axes
// are tested by projection instead.
inline const std::array<int, 2>* EdgeFaces(const PosedPolyhedron& poly, int e) {
  const auto& faces = poly.topology->edge_faces;
  if (e >= static_cast<int>(faces.size()) || faces[e][0] < 0 || faces[e][1] < 0) return nullptr;
  return &faces[e];
}

// The cube [-1, 1]^3: 8 vertices (index bits x, y, z), 6 faces, 12 edges.
const ConvexHull& UnitBoxTopology();

// A box's frame and size, taken from its body once per pair and shared by
// the closed-form box-box steps (box_box_sat.h, box_box_manifold.h).
struct BoxPose {
  Mat3 R;  // rotation, body to world
  Vec3 h;  // m, half extents
  Vec3 x;  // m, world, centre
  explicit BoxPose(const RigidBody& body) : R(body.Rotation()), h(body.shape.half_extents), x(body.x) {}
};

// World position of vertex v (index bits x, y, z) of the unit box topology
// scaled to the box: the expression PosePolyhedron poses every vertex with,
// so that a box posed vertex by vertex equals the posed box bit for bit.
inline Vec3 PosedVertex(const Mat3& R, const Vec3& scale, const Vec3& x, const Vec3& unit_vertex) {
  return R * unit_vertex.cwiseProduct(scale) + x;
}
// Face f = 2i + s of a box (outward normal (-1)^s R e_i, topology order
// +x, -x, +y, -y, +z, -z) as PosePolyhedron poses it: n . p = offset on it.
inline Vec3 BoxFaceNormal(const Mat3& R, int f) { return f % 2 == 0 ? Vec3(R.col(f / 2)) : Vec3(-R.col(f / 2)); }
inline double BoxFaceOffset(const Vec3& n, const Vec3& x, const Vec3& h, int f) { return n.dot(x) + h[f / 2]; }
inline Vec3 BoxVertex(const BoxPose& box, int v) {
  const Vec3 corner((v & 1) ? 1.0 : -1.0, (v & 2) ? 1.0 : -1.0, (v & 4) ? 1.0 : -1.0);
  return PosedVertex(box.R, box.h, box.x, corner);
}

// Fills `out` for a box or convex body; returns false for other shapes or a
// convex body without a hull.
bool PosePolyhedron(const RigidBody& body, PosedPolyhedron* out);

// Interval [lo, hi] of the vertices projected on `axis`.
void ProjectPolyhedron(const PosedPolyhedron& poly, const Vec3& axis, double* lo, double* hi);

// min over the vertices of n . v. Hulls of kDescentMinVertices vertices or
// more descend their vertex graph (DescendVertexGraph) from vertex *start,
// which is set to the minimiser: a hull of hundreds of vertices takes a few
// dozen dot products where a scan takes them all, for the same vertex value.
// Smaller ones, and topologies without the graph, are scanned.
double MinProjection(const PosedPolyhedron& poly, const Vec3& n, int* start);

// Index of the vertex with the largest projection on `direction`.
int SupportVertex(const PosedPolyhedron& poly, const Vec3& direction);

}  // namespace contactsim
