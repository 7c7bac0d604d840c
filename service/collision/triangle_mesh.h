// A static triangle mesh: welded vertices, triangles, each triangle's
// normal and active edges (triangle_surface.h), and a bounding-volume tree
// over the triangles' boxes (box_tree.h), so that colliding a body with the
// mesh costs the triangles near the body, not the mesh.
//
// Built once from vertices and indices (a command's, or a mesh file's read
// by service/model/mesh_reader.h). Input rules (docs/physics.md, "Triangle
// meshes and heightfields"): vertices finite, indices in range, a multiple
// of three of them; vertices at exactly the same position are welded, so
// that a file that repeats them per triangle (STL) still has adjacency;
// triangles of zero area are dropped and counted; an open or non-manifold
// mesh is allowed (a static surface needs no inside).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "service/collision/aabb.h"
#include "service/collision/box_tree.h"
#include "service/collision/surface_triangle.h"
#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

// Most triangles of one mesh: 2^20 triangles are ~100 MB with the tree.
constexpr int kMaxMeshTriangles = 1 << 20;

struct TriangleMesh {
  std::vector<Vec3> vertices;                 // m, body frame (scaled, welded)
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from the front
  std::vector<Vec3> normals;                  // unit, one per triangle
  std::vector<uint8_t> active_edges;          // per triangle, bit k: edge k -> k + 1
  std::vector<uint8_t> convex_edges;          // per triangle, the same bits for SurfaceTriangle::convex_edges
  std::vector<Aabb> boxes;                    // m, body frame, one per triangle
  Aabb bounds;                                // m, body frame, every triangle
  BoxTree tree;

  SurfaceTriangle Triangle(int t) const;
};

struct MeshBuildReport {
  int dropped_degenerate = 0;  // triangles of zero area left out
  int welded_vertices = 0;     // vertices merged into an earlier one at the same position
};

// Builds the mesh from `vertices` (m, scaled by `scale` > 0) and `indices`
// (three per triangle). Fails, naming the field and value, on an empty
// mesh, a count not a multiple of three, an index out of range, a
// non-finite vertex, more than kMaxMeshTriangles, or no triangle of
// nonzero area.
Status BuildTriangleMesh(const std::vector<Vec3>& vertices, const std::vector<int>& indices, double scale,
                         std::shared_ptr<const TriangleMesh>* mesh, MeshBuildReport* report = nullptr);

}  // namespace contactsim
