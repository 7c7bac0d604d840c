#include "service/collision/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "service/collision/triangle_surface.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

// Welds vertices at bitwise-equal positions, in first-seen order, and
// remaps the indices; returns the number merged.
int WeldVertices(std::vector<Vec3>* vertices, std::vector<int>* indices) {
  std::map<std::array<double, 3>, int> seen;
  std::vector<int> remap(vertices->size());
  std::vector<Vec3> kept;
  kept.reserve(vertices->size());
  for (size_t i = 0; i < vertices->size(); ++i) {
    const Vec3& v = (*vertices)[i];
    const auto [it, inserted] = seen.emplace(std::array<double, 3>{v.x(), v.y(), v.z()}, static_cast<int>(kept.size()));
    if (inserted) kept.push_back(v);
    remap[i] = it->second;
  }
  for (int& k : *indices) k = remap[k];
  const int merged = static_cast<int>(vertices->size() - kept.size());
  *vertices = std::move(kept);
  return merged;
}

// Each edge's activity from its neighbours: an edge shared by exactly two
// triangles is active when convex (EdgeIsActive), and convex by any angle
// beyond round-off (kConvexEdgeAngle); others are both.
void ClassifyEdges(TriangleMesh* mesh) {
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edges;  // (lo, hi) -> (triangle, edge)
  const int n = static_cast<int>(mesh->triangles.size());
  for (int t = 0; t < n; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = mesh->triangles[t][k], b = mesh->triangles[t][(k + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(t, k);
    }
  }
  mesh->active_edges.assign(n, 7);
  mesh->convex_edges.assign(n, 7);
  for (const auto& [key, sides] : edges) {
    if (sides.size() != 2) continue;  // open or non-manifold: active
    for (int s = 0; s < 2; ++s) {
      const auto [t, k] = sides[s];
      const auto [u, j] = sides[1 - s];
      const auto& tri = mesh->triangles[t];
      const Vec3& a = mesh->vertices[tri[k]];
      const Vec3& b = mesh->vertices[tri[(k + 1) % 3]];
      const Vec3& w = mesh->vertices[mesh->triangles[u][(j + 2) % 3]];
      if (!EdgeIsActive(mesh->normals[t], a, b, w)) mesh->active_edges[t] &= ~(1u << k);
      if (!EdgeIsActive(mesh->normals[t], a, b, w, kConvexEdgeAngle)) mesh->convex_edges[t] &= ~(1u << k);
    }
  }
}

Status CheckInput(const std::vector<Vec3>& vertices, const std::vector<int>& indices, double scale) {
  if (!(std::isfinite(scale) && scale > 0.0)) {
    return Status::InvalidArgument("mesh scale must be finite and > 0, got " + FormatValue(scale));
  }
  if (vertices.empty() || indices.empty()) {
    return Status::InvalidArgument("a mesh needs vertices and indices, got " + std::to_string(vertices.size()) +
                                   " vertices and " + std::to_string(indices.size()) + " indices");
  }
  if (indices.size() % 3 != 0) {
    return Status::InvalidArgument("mesh indices must be three per triangle, got " + std::to_string(indices.size()));
  }
  if (indices.size() / 3 > static_cast<size_t>(kMaxMeshTriangles)) {
    return Status::ResourceExhausted("a mesh has at most " + std::to_string(kMaxMeshTriangles) + " triangles, got " +
                                     std::to_string(indices.size() / 3));
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!IsFinite(vertices[i])) {
      return Status::InvalidArgument("mesh vertex " + std::to_string(i) + " is not finite");
    }
  }
  for (size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] < 0 || static_cast<size_t>(indices[i]) >= vertices.size()) {
      return Status::InvalidArgument("mesh index " + std::to_string(i) + " is " + std::to_string(indices[i]) +
                                     ", out of range for " + std::to_string(vertices.size()) + " vertices");
    }
  }
  return Status::Ok();
}

}  // namespace

SurfaceTriangle TriangleMesh::Triangle(int t) const {
  SurfaceTriangle tri;
  const auto& idx = triangles[t];
  tri.v = {vertices[idx[0]], vertices[idx[1]], vertices[idx[2]]};
  tri.normal = normals[t];
  tri.active_edges = active_edges[t];
  tri.convex_edges = convex_edges[t];
  tri.index = static_cast<uint32_t>(t);
  return tri;
}

Status BuildTriangleMesh(const std::vector<Vec3>& vertices, const std::vector<int>& indices, double scale,
                         std::shared_ptr<const TriangleMesh>* mesh, MeshBuildReport* report) {
  Status st = CheckInput(vertices, indices, scale);
  if (!st.ok()) return st;
  auto m = std::make_shared<TriangleMesh>();
  m->vertices.reserve(vertices.size());
  for (const Vec3& v : vertices) m->vertices.push_back(scale * v);
  std::vector<int> welded = indices;
  MeshBuildReport r;
  r.welded_vertices = WeldVertices(&m->vertices, &welded);
  for (size_t i = 0; i < welded.size(); i += 3) {
    SurfaceTriangle tri;
    if (!MakeSurfaceTriangle(m->vertices[welded[i]], m->vertices[welded[i + 1]], m->vertices[welded[i + 2]], &tri)) {
      ++r.dropped_degenerate;
      continue;
    }
    m->triangles.push_back({welded[i], welded[i + 1], welded[i + 2]});
    m->normals.push_back(tri.normal);
    Aabb box{tri.v[0], tri.v[0]};
    for (const Vec3& p : tri.v) {
      box.min = box.min.cwiseMin(p);
      box.max = box.max.cwiseMax(p);
    }
    m->boxes.push_back(box);
  }
  if (m->triangles.empty()) {
    return Status::InvalidArgument("every one of the mesh's " + std::to_string(indices.size() / 3) +
                                   " triangles has zero area");
  }
  ClassifyEdges(m.get());
  m->bounds = m->boxes[0];
  for (const Aabb& b : m->boxes) {
    m->bounds.min = m->bounds.min.cwiseMin(b.min);
    m->bounds.max = m->bounds.max.cwiseMax(b.max);
  }
  m->tree.Build(m->boxes);
  if (report != nullptr) *report = r;
  *mesh = std::move(m);
  return Status::Ok();
}

}  // namespace contactsim
