// contactsim's static triangle meshes and heightfields as Bullet shapes
// (bullet_runner.cpp): a mesh as a btBvhTriangleMeshShape over its welded
// vertices and triangles, a heightfield as a btHeightfieldTerrainShape over
// its grid of doubles, both with btInternalEdgeUtility's triangle info, the
// internal-edge correction Bullet offers against ghost collisions on shared
// edges (as contactsim's active edges, docs/physics.md, "Triangle meshes and
// heightfields").
//
// The heightfield is the same surface as contactsim's: Bullet's
// `flipQuadEdges` splits each cell along the diagonal from sample (x, j) to
// (x + 1, j + 1), the one height_field.h splits along; its samples are
// row-major with x along the row, as contactsim's; its local origin is the
// middle of its box, so the body is placed at the grid's centre lifted by
// (min height + max height) / 2.
#pragma once

#include <BulletCollision/CollisionDispatch/btInternalEdgeUtility.h>
#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <btBulletDynamicsCommon.h>

#include <memory>
#include <vector>

#include "service/collision/height_field.h"
#include "service/collision/triangle_mesh.h"

namespace contactsim::bench {

// What a Bullet surface shape reads from and keeps: Bullet's mesh and
// heightfield shapes do not copy their data.
struct BulletSurface {
  std::vector<btScalar> vertices;  // x y z per vertex
  std::vector<int> indices;        // three per triangle
  std::unique_ptr<btTriangleIndexVertexArray> mesh_data;
  std::unique_ptr<btTriangleInfoMap> edge_info;
  std::unique_ptr<btCollisionShape> shape;
  btVector3 offset{0, 0, 0};  // body frame: where the shape's origin lies
};

inline std::unique_ptr<BulletSurface> MakeBulletMesh(const TriangleMesh& mesh) {
  auto s = std::make_unique<BulletSurface>();
  for (const Vec3& v : mesh.vertices) s->vertices.insert(s->vertices.end(), {v.x(), v.y(), v.z()});
  for (const auto& t : mesh.triangles) s->indices.insert(s->indices.end(), {t[0], t[1], t[2]});
  s->mesh_data = std::make_unique<btTriangleIndexVertexArray>(
      static_cast<int>(mesh.triangles.size()), s->indices.data(), 3 * sizeof(int),
      static_cast<int>(mesh.vertices.size()), s->vertices.data(), 3 * sizeof(btScalar));
  auto shape = std::make_unique<btBvhTriangleMeshShape>(s->mesh_data.get(), true, true);
  s->edge_info = std::make_unique<btTriangleInfoMap>();
  btGenerateInternalEdgeInfo(shape.get(), s->edge_info.get());
  s->shape = std::move(shape);
  return s;
}

inline std::unique_ptr<BulletSurface> MakeBulletHeightfield(const HeightField& field) {
  auto s = std::make_unique<BulletSurface>();
  s->vertices.assign(field.heights.begin(), field.heights.end());
  auto shape = std::make_unique<btHeightfieldTerrainShape>(field.cols, field.rows, s->vertices.data(),
                                                           field.min_height, field.max_height, 2, true);
  shape->setLocalScaling(btVector3(field.spacing_x, field.spacing_y, 1.0));
  s->edge_info = std::make_unique<btTriangleInfoMap>();
  btGenerateInternalEdgeInfo(shape.get(), s->edge_info.get());
  s->offset = btVector3(0, 0, 0.5 * (field.min_height + field.max_height));
  s->shape = std::move(shape);
  return s;
}

// gContactAddedCallback for the surfaces' bodies (CF_CUSTOM_MATERIAL_CALLBACK):
// moves a contact normal on an internal edge towards the triangle's face
// normal. A convex-concave pair's manifold has the convex body first and
// the surface's triangle second (btConvexTriangleCallback), the order
// btAdjustInternalEdgeContacts takes them in reversed.
inline bool AdjustInternalEdges(btManifoldPoint& cp, const btCollisionObjectWrapper* convex, int, int,
                                const btCollisionObjectWrapper* triangle, int part, int index) {
  btAdjustInternalEdgeContacts(cp, triangle, convex, part, index);
  return true;
}

}  // namespace contactsim::bench
