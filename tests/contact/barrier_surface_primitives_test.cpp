// Tests of the barrier method's distances against a triangle surface
// (surface_primitives.h): a flat tessellated floor gives a body's height and
// the floor's normal wherever it is, over shared edges and vertices (no
// ghost edge), a convex ridge gives the exact edge-edge and vertex-face
// distances, and the CCD over a flat part stops exactly at the target.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "service/collision/triangle_mesh.h"
#include "service/contact/barrier/additive_ccd.h"
#include "service/contact/barrier/affine_body.h"
#include "service/contact/barrier/contact_primitives.h"
#include "service/contact/barrier/surface_primitives.h"
#include "tests/collision/grid_mesh.h"

namespace contactsim {
namespace {

constexpr double kReach = 1e-2;   // m, the solver's at the default d_hat
constexpr double kDepth = 2e-5;   // m, its signed depth

// A flat 1 m floor of 0.1 m cells through the origin.
BodyGeometry Floor(const Shape& shape) {
  BodyGeometry g = MakeBodyGeometry(shape);
  g.surface.reach = kReach;
  return g;
}

// The smallest distance of `body` at (p, R) to the surface over every pair
// of `kind`, with its normal (from the body to the surface).
PairDistance Smallest(const BodyGeometry& body, const Vec3& p, const Mat3& R, const BodyGeometry& surface,
                      PrimitiveKind kind) {
  std::vector<PrimitivePair> pairs;
  EnumeratePrimitivePairs(body, surface, &pairs);
  PairDistance best;
  best.d = 1e300;
  for (const PrimitivePair& pair : pairs) {
    if (pair.kind != kind) continue;
    const PairDistance d =
        EvaluatePair(body, p, R, surface, Vec3::Zero(), Mat3::Identity(), pair, kDepth, {0.0, 1e-3});
    if (d.d < best.d) best = d;
  }
  return best;
}

// Verifies the ghost edge: a sphere's centre 0.3 mm above the floor, placed
// on a shared edge, 10 um beside it, on a diagonal and on a vertex where six
// triangles meet, is at its height with the floor's normal, as over a
// plane; a sum over the triangles within d_hat would add the neighbour's
// pair, sqrt(h^2 + s^2) away with a tilted normal.
TEST(BarrierSurfacePrimitives, FlatFloorGivesTheHeightOverEdgesAndVertices) {
  const Shape shape = Shape::Mesh(testing::BuildGrid(10, 0.1));
  const BodyGeometry floor = Floor(shape);
  const BodyGeometry ball = MakeBodyGeometry(Shape::Sphere(0.05));
  const double h = 3e-4;
  for (const Vec3& xy : {Vec3(0.1, 0.03, 0), Vec3(0.10001, 0.03, 0), Vec3(0.03, 0.03, 0), Vec3(0.1, 0.1, 0),
                         Vec3(0.0, 0.0, 0), Vec3(0.047, 0.012, 0)}) {
    const PairDistance d =
        Smallest(ball, xy + Vec3(0, 0, 0.05 + h), Mat3::Identity(), floor, PrimitiveKind::kPointSurface);
    EXPECT_NEAR(d.d, h, 1e-15) << xy.transpose();
    EXPECT_NEAR(d.n.z(), -1.0, 1e-15) << xy.transpose();
  }
}

// Verifies that over a flat floor a box's edges and faces pair with nothing
// (flat edges and vertices are not convex), so its four corners carry it
// as on a plane, each at its height.
TEST(BarrierSurfacePrimitives, FlatFloorPairsOnlyTheCorners) {
  const Shape shape = Shape::Mesh(testing::BuildGrid(10, 0.1));
  const BodyGeometry floor = Floor(shape);
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3::Constant(0.1)));
  const Vec3 p(0.013, 0.027, 0.1 + 2e-4);
  EXPECT_NEAR(Smallest(box, p, Mat3::Identity(), floor, PrimitiveKind::kPointSurface).d, 2e-4, 1e-15);
  EXPECT_EQ(Smallest(box, p, Mat3::Identity(), floor, PrimitiveKind::kEdgeSurface).d, kReach);
  EXPECT_EQ(Smallest(box, p, Mat3::Identity(), floor, PrimitiveKind::kTriangleSurface).d, kReach);
}

// A roof: two triangles meeting in a convex ridge along y at height 0.1 m,
// sloping down to z = 0 at x = -+1.
Shape Roof() {
  const std::vector<Vec3> v = {Vec3(-1, -1, 0), Vec3(0, -1, 0.1), Vec3(0, 1, 0.1), Vec3(-1, 1, 0),
                               Vec3(1, -1, 0),  Vec3(1, 1, 0)};
  const std::vector<int> idx = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
  std::shared_ptr<const TriangleMesh> mesh;
  EXPECT_TRUE(BuildTriangleMesh(v, idx, 1.0, &mesh).ok());
  return Shape::Mesh(mesh);
}

// Verifies the convex ridge: a box edge along x lying 0.5 mm above the
// ridge (its corners far down the slopes) is 0.5 mm from the surface by its
// edge pair with the crossing ridge, normal straight down, while its
// corners are 3 cm away (beyond the reach); and a box face held level 0.4 mm above the
// ridge is 0.4 mm from the ridge's end vertices by its face pairs.
TEST(BarrierSurfacePrimitives, ConvexRidgeGivesEdgeAndVertexDistances) {
  const Shape shape = Roof();
  const BodyGeometry roof = Floor(shape);
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3(0.3, 0.05, 0.05)));
  const PairDistance edge =
      Smallest(box, Vec3(0, 0.02, 0.1 + 0.05 + 5e-4), Mat3::Identity(), roof, PrimitiveKind::kEdgeSurface);
  EXPECT_NEAR(edge.d, 5e-4, 1e-12);
  EXPECT_NEAR(edge.n.z(), -1.0, 1e-9);
  EXPECT_EQ(Smallest(box, Vec3(0, 0.02, 0.1 + 0.05 + 5e-4), Mat3::Identity(), roof, PrimitiveKind::kPointSurface).d,
            kReach);
  // a plate over the ridge's end at y = 1: the ridge vertex (0, 1, 0.1) under its face
  const BodyGeometry plate = MakeBodyGeometry(Shape::Box(Vec3(0.2, 0.2, 0.05)));
  const PairDistance face = Smallest(plate, Vec3(0.01, 0.95, 0.1 + 0.05 + 4e-4), Mat3::Identity(), roof,
                                     PrimitiveKind::kTriangleSurface);
  EXPECT_NEAR(face.d, 4e-4, 1e-12);
  EXPECT_NEAR(face.n.z(), -1.0, 1e-9);
}

// Verifies the flat CCD: a box sliding 17 mm along a floor 10 um below it
// takes the whole step, and one falling 1 cm onto it stops where its
// lowest corner reaches the target, to round-off.
TEST(BarrierSurfacePrimitives, FlatSurfaceCcdIsExact) {
  const Shape shape = Shape::Mesh(testing::BuildGrid(10, 0.1));
  const BodyGeometry floor = Floor(shape);
  const BodyGeometry box = MakeBodyGeometry(Shape::Box(Vec3::Constant(0.1)));
  const Vec12 q = AffineFromPose(Vec3(0.013, 0.027, 0.1 + 1e-5), Mat3::Identity());
  const Vec12 q_floor = AffineFromPose(Vec3::Zero(), Mat3::Identity());
  for (int i = 0; i < 8; ++i) {
    CcdPair p;
    p.a = &box;
    p.b = &floor;
    p.qa = q;
    p.qb = q_floor;
    p.dqa = Vec12::Zero();
    p.dqb = Vec12::Zero();
    p.pair = {PrimitiveKind::kPointSurface, i, 0, false};
    p.dqa.head<3>() = Vec3(0.017, 0.0, 0.0);
    EXPECT_EQ(AdditiveCcd(p, 0.1, 1.0), 1.0) << "corner " << i;
    p.dqa.head<3>() = Vec3(0.0, 0.0, -1e-2);
    if (box.points[i].z() < 0.0) EXPECT_NEAR(AdditiveCcd(p, 0.1, 1.0), 0.9 * 1e-5 / 1e-2, 1e-12) << "corner " << i;
  }
}

}  // namespace
}  // namespace contactsim
