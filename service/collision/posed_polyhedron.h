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
