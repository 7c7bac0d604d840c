// Triangle meshes and heightfields in the narrowphase: the mesh builder's
// checks, the edge rule (no normal from a flat or concave edge), the box
// tree's query against brute force, agreement with a plane, and ray casts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "service/collision/height_field.h"
#include "service/collision/narrowphase.h"
#include "service/collision/ray_shape.h"
#include "service/collision/triangle_mesh.h"
#include "service/collision/triangle_surface.h"
#include "service/physics/cylinder_hull.h"
#include "tests/collision/grid_mesh.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

using testing::BuildGrid;
using testing::GridMesh;
using testing_util::Box;
using testing_util::Capsule;
using testing_util::Ground;
using testing_util::MakeBody;
using testing_util::RandomRotation;
using testing_util::Sphere;

constexpr double kSurfaceTol = 1e-9;

RigidBody MeshBody(std::shared_ptr<const TriangleMesh> mesh, const Vec3& x = Vec3::Zero()) {
  return MakeBody(100, Shape::Mesh(std::move(mesh)), x);
}

Status Build(const std::vector<Vec3>& v, const std::vector<int>& i, MeshBuildReport* report = nullptr) {
  std::shared_ptr<const TriangleMesh> mesh;
  return BuildTriangleMesh(v, i, 1.0, &mesh, report);
}

// Verifies that bad meshes are refused with a message naming the problem:
// empty, a count not a multiple of three, an index out of range, a NaN or
// infinite vertex, a bad scale, and triangles all of zero area.
TEST(TriangleMeshTest, RefusesBadInputNamingIt) {
  const std::vector<Vec3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  EXPECT_NE(Build({}, {}).message().find("needs vertices and indices"), std::string::npos);
  EXPECT_NE(Build(tri, {0, 1}).message().find("three per triangle"), std::string::npos);
  EXPECT_NE(Build(tri, {0, 1, 3}).message().find("out of range"), std::string::npos);
  EXPECT_NE(Build(tri, {0, 1, -1}).message().find("out of range"), std::string::npos);
  auto bad = tri;
  bad[1].x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(Build(bad, {0, 1, 2}).message().find("vertex 1 is not finite"), std::string::npos);
  bad[1].x() = std::numeric_limits<double>::infinity();
  EXPECT_NE(Build(bad, {0, 1, 2}).message().find("not finite"), std::string::npos);
  std::shared_ptr<const TriangleMesh> mesh;
  EXPECT_NE(BuildTriangleMesh(tri, {0, 1, 2}, 0.0, &mesh).message().find("scale"), std::string::npos);
  EXPECT_EQ(mesh, nullptr);
  const std::vector<Vec3> line = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  EXPECT_NE(Build(line, {0, 1, 2, 0, 0, 1}).message().find("zero area"), std::string::npos);
}

// Verifies that zero-area triangles are dropped and counted, and that
// vertices repeated per triangle (as STL stores them) are welded, so that
// the edge between two coplanar triangles is found and is inactive.
TEST(TriangleMeshTest, DropsDegenerateTrianglesAndWeldsRepeatedVertices) {
  const std::vector<Vec3> v = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0),
                               Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(2, 0, 0)};
  MeshBuildReport report;
  std::shared_ptr<const TriangleMesh> mesh;
  ASSERT_TRUE(BuildTriangleMesh(v, {0, 1, 2, 3, 4, 5, 0, 1, 6}, 2.0, &mesh, &report).ok());
  EXPECT_EQ(report.dropped_degenerate, 1);
  EXPECT_EQ(report.welded_vertices, 2);
  ASSERT_EQ(mesh->triangles.size(), 2u);
  EXPECT_NEAR(mesh->bounds.max.x(), 2.0, kSurfaceTol);  // scaled
  // the shared diagonal is edge 2 of the first triangle, edge 0 of the second
  EXPECT_EQ(mesh->active_edges[0], 0b011);
  EXPECT_EQ(mesh->active_edges[1], 0b110);
}

// Verifies the edge rule: an edge is active only when convex by more than
// 5 degrees; a flat, a slightly convex and a concave edge are inactive.
TEST(TriangleMeshTest, EdgeIsActiveOnlyWhenConvex) {
  const Vec3 n = Vec3::UnitZ(), a(0, 0, 0), b(1, 0, 0);
  EXPECT_FALSE(EdgeIsActive(n, a, b, Vec3(0.5, -1, 0)));                        // flat
  EXPECT_FALSE(EdgeIsActive(n, a, b, Vec3(0.5, -1, std::tan(0.04))));           // concave
  EXPECT_FALSE(EdgeIsActive(n, a, b, Vec3(0.5, -1, -std::tan(0.04))));          // convex by 2.3 degrees
  EXPECT_TRUE(EdgeIsActive(n, a, b, Vec3(0.5, -1, -std::tan(0.2))));            // convex by 11 degrees
  EXPECT_TRUE(EdgeIsActive(n, a, b, Vec3(0.5, 0, -1)));                         // a right-angled ridge
}

// Verifies the convex edges the barrier pairs with (surface_triangle.h,
// convex_edges): convex by any angle beyond round-off, so the ridge convex
// by 2.3 degrees that the edge rule leaves inactive is convex, while flat
// and concave edges are not; a flat grid's only convex edges are its
// border, as a mesh and as a heightfield.
TEST(TriangleMeshTest, ConvexEdgesAreConvexBeyondRoundOff) {
  const Vec3 n = Vec3::UnitZ(), a(0, 0, 0), b(1, 0, 0);
  EXPECT_FALSE(EdgeIsActive(n, a, b, Vec3(0.5, -1, 0), kConvexEdgeAngle));                // flat
  EXPECT_FALSE(EdgeIsActive(n, a, b, Vec3(0.5, -1, 1e-3), kConvexEdgeAngle));             // concave
  EXPECT_TRUE(EdgeIsActive(n, a, b, Vec3(0.5, -1, -std::tan(0.04)), kConvexEdgeAngle));   // 2.3 degrees
  EXPECT_TRUE(EdgeIsActive(n, a, b, Vec3(0.5, -1, -1e-5), kConvexEdgeAngle));             // 1e-5 rad
  const auto mesh = BuildGrid(4, 0.5);
  std::shared_ptr<const HeightField> field;
  ASSERT_TRUE(BuildHeightField(5, 5, std::vector<double>(25, 0.0), 0.5, 0.5, &field).ok());
  const Aabb all{Vec3::Constant(-2.0), Vec3::Constant(2.0)};
  for (const Shape& shape : {Shape::Mesh(mesh), Shape::Heightfield(field)}) {
    int convex = 0;
    ForEachSurfaceTriangle(shape, all, [&](const SurfaceTriangle& t) {
      for (int k = 0; k < 3; ++k) {
        if (!(t.convex_edges & (1u << k))) continue;
        ++convex;
        // on the border: both ends on the grid's edge
        const Vec3 m = 0.5 * (t.v[k] + t.v[(k + 1) % 3]);
        EXPECT_NEAR(std::max(std::abs(m.x()), std::abs(m.y())), 1.0, 1e-12) << ShapeTypeName(shape.type);
      }
    });
    EXPECT_EQ(convex, 16) << ShapeTypeName(shape.type);
  }
}

// Verifies the box tree's query: the triangles it visits for random boxes
// are exactly those whose boxes overlap, over a 20,000-triangle grid.
TEST(TriangleMeshTest, TreeQueryMatchesBruteForce) {
  const auto mesh = BuildGrid(100, 0.1);
  ASSERT_EQ(mesh->triangles.size(), 20000u);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-6.0, 6.0), s(0.0, 0.5);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 c{u(rng), u(rng), s(rng) - 0.25};
    const Vec3 h{s(rng), s(rng), s(rng)};
    const Aabb box{c - h, c + h};
    std::vector<int> visited;
    mesh->tree.Overlap(box, [&](int t) {
      if (mesh->boxes[t].Overlaps(box)) visited.push_back(t);
    });
    std::vector<int> brute;
    for (int t = 0; t < static_cast<int>(mesh->boxes.size()); ++t) {
      if (mesh->boxes[t].Overlaps(box)) brute.push_back(t);
    }
    std::sort(visited.begin(), visited.end());
    EXPECT_EQ(visited, brute) << "trial " << trial;
  }
}

// The contacts of `body` with a grid floor (mesh, or the same heightfield)
// and with a plane at z = 0.
ContactSet Contacts(const RigidBody& body, const RigidBody& surface) {
  ContactSet out;
  Collide(body, 0, surface, 1, 1e-3, &out);
  return out;
}

void ExpectAllNormalsDown(const ContactSet& contacts, const char* what) {
  for (const Contact& c : contacts) {
    EXPECT_NEAR(c.normal.z(), -1.0, 1e-9) << what << " normal " << c.normal.transpose();
  }
}

// Verifies no ghost collisions: every shape straddling, or with a corner
// just past, the shared edges and vertices of a flat grid, sunk 1 mm,
// gets only the face normal, the plane's depth, and at most four points.
TEST(CollideSurfaceTest, FlatGridGivesThePlaneContactAcrossEdgesAndVertices) {
  const RigidBody floor = MeshBody(BuildGrid(20, 0.1));
  const RigidBody plane = Ground(101);
  const double sink = 1e-3;
  for (const Vec3& at : {Vec3(0.0, 0.0, 0.0), Vec3(0.05, 0.0, 0.0), Vec3(0.0, 0.05, 0.0), Vec3(0.0001, 0.0002, 0.0),
                         Vec3(0.1 - 1e-5, 0.03, 0.0), Vec3(0.033, 0.033, 0.0)}) {
    const RigidBody box = Box(1, Vec3(0.1, 0.1, 0.1), at + Vec3(0, 0, 0.1 - sink));
    const RigidBody ball = Sphere(2, 0.1, at + Vec3(0, 0, 0.1 - sink));
    const RigidBody rod = Capsule(3, 0.05, 0.1, at + Vec3(0, 0, 0.05 - sink), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX())));
    for (const RigidBody* b : {&box, &ball, &rod}) {
      const ContactSet mesh = Contacts(*b, floor);
      const ContactSet flat = Contacts(*b, plane);
      ASSERT_FALSE(mesh.empty()) << ShapeTypeName(b->shape.type) << " at " << at.transpose();
      EXPECT_LE(mesh.size(), 4u);
      ExpectAllNormalsDown(mesh, ShapeTypeName(b->shape.type));
      double deepest = -1, deepest_plane = -1;
      for (const Contact& c : mesh) deepest = std::max(deepest, c.depth);
      for (const Contact& c : flat) deepest_plane = std::max(deepest_plane, c.depth);
      EXPECT_NEAR(deepest, deepest_plane, 1e-9) << ShapeTypeName(b->shape.type) << " at " << at.transpose();
    }
  }
}

// Verifies the other pieces: a cylinder (a hull) lying on its side and a
// compound of a box and two spheres, sunk 1 mm into the grid across its
// edges, get only the face normal, and the plane's deepest depth.
TEST(CollideSurfaceTest, HullsAndCompoundsGetThePlaneContact) {
  const RigidBody floor = MeshBody(BuildGrid(20, 0.1));
  std::shared_ptr<const ConvexHull> cylinder;
  ASSERT_TRUE(BuildCylinderHull(0.05, 0.3, &cylinder).ok());
  const Quat side(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()));
  const RigidBody lying = testing_util::Convex(1, cylinder, Vec3(0.013, 0.0, 0.05 - 1e-3), side);
  const RigidBody dumbbell = MakeBody(2, Shape::Compound({{Shape::Box(Vec3(0.2, 0.02, 0.02)), Vec3::Zero(), Quat::Identity()},
                                                          {Shape::Sphere(0.05), Vec3(-0.2, 0, 0), Quat::Identity()},
                                                          {Shape::Sphere(0.05), Vec3(0.2, 0, 0), Quat::Identity()}}),
                                      Vec3(0.0, 0.1, 0.05 - 1e-3));
  for (const RigidBody* b : {&lying, &dumbbell}) {
    const ContactSet out = Contacts(*b, floor);
    ASSERT_FALSE(out.empty()) << ShapeTypeName(b->shape.type);
    ExpectAllNormalsDown(out, ShapeTypeName(b->shape.type));
    double deepest = -1, deepest_plane = -1;
    for (const Contact& c : out) deepest = std::max(deepest, c.depth);
    for (const Contact& c : Contacts(*b, Ground(101))) deepest_plane = std::max(deepest_plane, c.depth);
    EXPECT_NEAR(deepest, deepest_plane, 1e-9) << ShapeTypeName(b->shape.type);
  }
}

// Verifies that a box sliding with a corner leading, sunk 0.1 mm into a
// flat grid, meets the next triangle's edge with no sideways normal at
// every offset across a cell (the case a triangle alone gets wrong).
TEST(CollideSurfaceTest, LeadingCornerMeetsNoEdgeNormal) {
  const RigidBody floor = MeshBody(BuildGrid(20, 0.1));
  const Quat yaw(Eigen::AngleAxisd(0.3, Vec3::UnitZ()));
  for (int k = 0; k < 100; ++k) {
    const RigidBody box = Box(1, Vec3(0.1, 0.05, 0.05), Vec3(0.001 * k, 0.0013 * k, 0.05 - 1e-4), yaw);
    ExpectAllNormalsDown(Contacts(box, floor), "box");
  }
}

// Verifies that a convex edge stays active: a ball pressed against a
// right-angled step's edge is pushed out along the edge's bisector.
TEST(CollideSurfaceTest, ConvexEdgeKeepsItsNormal) {
  // a step: top face z = 0 for x < 0, wall face x = 0 below it
  const std::vector<Vec3> v = {Vec3(-1, -1, 0), Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(-1, 1, 0),
                               Vec3(0, -1, -1), Vec3(0, 1, -1)};
  std::shared_ptr<const TriangleMesh> mesh;
  ASSERT_TRUE(BuildTriangleMesh(v, {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2}, 1.0, &mesh).ok());
  const RigidBody step = MeshBody(mesh);
  const double r = 0.1;
  const Vec3 centre = Vec3(1, 0, 1).normalized() * (r - 1e-3);
  const ContactSet out = Contacts(Sphere(1, r, centre), step);
  ASSERT_FALSE(out.empty());
  for (const Contact& c : out) EXPECT_NEAR(c.normal.dot(-Vec3(1, 0, 1).normalized()), 1.0, 1e-6) << c.normal.transpose();
}

// Verifies the heightfield against the same grid as a mesh: its stored
// edge bits are its neighbours', and a box and a ball over a wavy field get
// the same contacts (points, normals, depths) whichever way the triangles
// were made.
TEST(CollideSurfaceTest, HeightfieldEqualsItsMesh) {
  const int n = 16;
  const double cell = 0.1;
  std::vector<double> heights;
  auto h = [](int r, int c) { return 0.05 * std::sin(0.7 * r) * std::cos(0.5 * c); };
  for (int r = 0; r <= n; ++r) {
    for (int c = 0; c <= n; ++c) heights.push_back(h(r, c));
  }
  std::shared_ptr<const HeightField> field;
  ASSERT_TRUE(BuildHeightField(n + 1, n + 1, heights, cell, cell, &field).ok());
  // the edge bits stored when the field was built are those its
  // neighbours give, on a field with edges of both kinds
  int active = 0;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      for (int half : {0, 1}) {
        const SurfaceTriangle stored = field->Triangle(r, c, half);
        const SurfaceTriangle found = field->TriangleWithNeighbours(r, c, half);
        EXPECT_EQ(stored.active_edges, found.active_edges) << r << ", " << c << ", " << half;
        EXPECT_EQ(stored.convex_edges, found.convex_edges) << r << ", " << c << ", " << half;
        for (int k = 0; k < 3; ++k) active += (stored.active_edges >> k) & 1;
      }
    }
  }
  EXPECT_GT(active, 0);
  EXPECT_LT(active, 6 * n * n);
  // the mesh takes the field's own samples, so that both hold the same
  // vertices to the last bit and only the way the triangles are made differs
  testing::MeshData m = GridMesh(n, cell);
  for (int r = 0; r <= n; ++r) {
    for (int c = 0; c <= n; ++c) m.vertices[r * (n + 1) + c] = field->Sample(r, c);
  }
  std::shared_ptr<const TriangleMesh> mesh;
  ASSERT_TRUE(BuildTriangleMesh(m.vertices, m.indices, 1.0, &mesh).ok());
  const RigidBody as_field = MakeBody(100, Shape::Heightfield(field));
  const RigidBody as_mesh = MeshBody(mesh);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  size_t compared = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const Vec3 at{u(rng), u(rng), 0.1};
    for (const RigidBody& b : {Box(1, Vec3(0.1, 0.07, 0.05), at, RandomRotation(rng)), Sphere(1, 0.1, at)}) {
      ContactSet a = Contacts(b, as_field), c = Contacts(b, as_mesh);
      const auto by_point = [](const Contact& x, const Contact& y) {
        return std::lexicographical_compare(x.point.data(), x.point.data() + 3, y.point.data(), y.point.data() + 3);
      };
      std::sort(a.begin(), a.end(), by_point);
      std::sort(c.begin(), c.end(), by_point);
      ASSERT_EQ(a.size(), c.size()) << "trial " << trial;
      compared += a.size();
      for (size_t k = 0; k < a.size(); ++k) {
        EXPECT_NEAR((a[k].point - c[k].point).norm(), 0.0, 1e-12);
        EXPECT_NEAR(a[k].depth, c[k].depth, 1e-12);
      }
    }
  }
  EXPECT_GT(compared, 50u);
}

// Verifies heightfield input checks: too few samples, a wrong count, a
// non-finite height, a bad spacing.
TEST(HeightFieldTest, RefusesBadInputNamingIt) {
  std::shared_ptr<const HeightField> f;
  EXPECT_NE(BuildHeightField(1, 3, {0, 0, 0}, 1, 1, &f).message().find("at least 2 x 2"), std::string::npos);
  EXPECT_NE(BuildHeightField(2, 3, {0, 0, 0, 0}, 1, 1, &f).message().find("rows x cols"), std::string::npos);
  EXPECT_NE(BuildHeightField(2, 2, {0, 0, NAN, 0}, 1, 1, &f).message().find("height 2 (row 1, col 0)"),
            std::string::npos);
  EXPECT_NE(BuildHeightField(2, 2, {0, 0, 0, 0}, 0, 1, &f).message().find("spacing"), std::string::npos);
  EXPECT_EQ(f, nullptr);
}

// Verifies ray casts: straight down onto a grid mesh and a heightfield hits
// the surface height with the face normal; from below passes through.
TEST(CollideSurfaceTest, RaysHitTheFrontOfMeshesAndHeightfields) {
  const auto mesh = BuildGrid(10, 0.2);
  std::shared_ptr<const HeightField> field;
  ASSERT_TRUE(BuildHeightField(3, 3, {0, 0, 0, 0, 0.5, 0, 0, 0, 0}, 1.0, 1.0, &field).ok());
  RayShapeHit hit;
  ASSERT_EQ(RayCastShape(Shape::Mesh(mesh), Vec3(0.31, -0.27, 2), -Vec3::UnitZ(), 10, &hit), RayShapeResult::kHit);
  EXPECT_NEAR(hit.t, 2.0, kSurfaceTol);
  EXPECT_NEAR(hit.normal.z(), 1.0, kSurfaceTol);
  EXPECT_EQ(RayCastShape(Shape::Mesh(mesh), Vec3(0.31, -0.27, -2), Vec3::UnitZ(), 10, &hit), RayShapeResult::kMiss);
  EXPECT_EQ(RayCastShape(Shape::Mesh(mesh), Vec3(0.31, -0.27, 2), -Vec3::UnitZ(), 1.5, &hit), RayShapeResult::kMiss);
  ASSERT_EQ(RayCastShape(Shape::Heightfield(field), Vec3(0, 0, 3), -Vec3::UnitZ(), 10, &hit), RayShapeResult::kHit);
  EXPECT_NEAR(hit.t, 2.5, kSurfaceTol);
}


// Verifies that a vertical ray exactly on any of the grid's four borders, and
// at its corners, hits the heightfield: a query box whose low side lies on
// the upper border still touches the last cell, as on the lower border.
TEST(CollideSurfaceTest, RaysOnTheHeightfieldBorderHit) {
  std::shared_ptr<const HeightField> field;
  ASSERT_TRUE(BuildHeightField(3, 4, std::vector<double>(12, 0.25), 0.5, 1.0, &field).ok());
  const double hx = 0.5 * 3 * 0.5, hy = 0.5 * 2 * 1.0;  // half extents of the grid
  for (const Vec3& p : {Vec3(hx, 0.1, 2), Vec3(-hx, 0.1, 2), Vec3(0.1, hy, 2), Vec3(0.1, -hy, 2), Vec3(hx, hy, 2),
                       Vec3(-hx, -hy, 2)}) {
    RayShapeHit hit;
    ASSERT_EQ(RayCastShape(Shape::Heightfield(field), p, -Vec3::UnitZ(), 10, &hit), RayShapeResult::kHit)
        << p.transpose();
    EXPECT_NEAR(hit.t, 1.75, kSurfaceTol);
  }
  RayShapeHit hit;
  EXPECT_EQ(RayCastShape(Shape::Heightfield(field), Vec3(hx + 1e-9, 0.1, 2), -Vec3::UnitZ(), 10, &hit),
            RayShapeResult::kMiss);
}

}  // namespace
}  // namespace contactsim
