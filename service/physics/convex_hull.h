// A convex polyhedron with its topology, as the narrowphase needs it:
// vertices, faces (outward unit normal, plane offset, vertex loop in
// counter-clockwise order seen from outside) and unique edges.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "service/physics/mass_properties.h"
#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

struct ConvexHull {
  struct Face {
    Vec3 normal;                // unit, outward, body frame
    double offset = 0.0;        // m, normal . p = offset for p on the face
    std::vector<int> vertices;  // indices into vertices, counter-clockwise from outside
  };
  std::vector<Vec3> vertices;            // m, body frame (centre of mass at the origin)
  std::vector<Face> faces;
  std::vector<std::array<int, 2>> edges; // each undirected edge once
  // The two faces on each edge (edge_faces[e][0] holds the edge as
  // edges[e][0] -> edges[e][1] in its loop), -1 where a face is missing:
  // their normals are the ends of the edge's arc on the Gauss map, which the
  // separating-axis test uses to skip edge pairs.
  std::vector<std::array<int, 2>> edge_faces;
  // The vertex graph along the edges, as compressed rows: the neighbours of
  // vertex v are neighbours[neighbour_start[v]] up to neighbours[neighbour_start[v + 1]].
  // A linear function over a convex polyhedron has no local minimum on this
  // graph but the global one, so the separating-axis test finds a support
  // vertex by descent over it instead of a scan of every vertex. Empty on a
  // topology built without ConnectEdgeFaces (then the vertices are scanned).
  std::vector<int> neighbour_start;
  std::vector<int> neighbours;
};

// Hulls with fewer vertices than this are scanned rather than descended: the
// descent's bookkeeping outweighs a scan of a few dozen vertices, and boxes
// and small hulls keep the scans' exact order of operations.
constexpr int kDescentMinVertices = 32;

// The vertex of least value(i) (a function linear in vertex i's position,
// evaluated as the caller's scan would), by descent over the vertex graph
// from vertex `start`: each step moves to the neighbour of least value, until
// none is less. Sets *min_value to that value. The hull must have its graph
// (neighbour_start.size() == vertices.size() + 1).
template <typename Value>
int DescendVertexGraph(const ConvexHull& hull, int start, const Value& value, double* min_value) {
  int v = start >= 0 && start < static_cast<int>(hull.vertices.size()) ? start : 0;
  double best = value(v);
  for (int from = -1; from != v;) {
    from = v;
    for (int k = hull.neighbour_start[from]; k < hull.neighbour_start[from + 1]; ++k) {
      const double p = value(hull.neighbours[k]);
      if (p < best) best = p, v = hull.neighbours[k];
    }
  }
  *min_value = best;
  return v;
}

// Fills hull->edge_faces from the face loops and edges, and the vertex graph
// from the edges (BuildConvexHull does; call it after building a hull's
// topology by hand).
void ConnectEdgeFaces(ConvexHull* hull);

// Builds the hull of a point cloud, merging coplanar faces. Fails with a
// message when there are fewer than four points, a non-finite coordinate,
// or all points are (nearly) coplanar. `centroid_out`, when given, receives
// the centre of mass of the solid hull in the input frame; the returned
// hull's vertices are shifted so that this point is the origin.
Status BuildConvexHull(const std::vector<Vec3>& points, std::shared_ptr<const ConvexHull>* hull,
                       Vec3* centroid_out = nullptr);

// Volume (m^3) and mass properties of the solid hull at uniform density,
// by the polyhedral mass integrals (Mirtich 1996, divergence theorem).
double ConvexHullVolume(const ConvexHull& hull);
MassProperties ConvexHullMassProperties(const ConvexHull& hull, double density);

}  // namespace contactsim
