#include "service/physics/convex_hull.h"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace contactsim {
namespace {

// Mass integrals are exact polynomials; 1e-9 relative leaves room for the
// round-off of summing a few hundred terms of size ~1.
constexpr double kMassRelTol = 1e-9;
// Points on the hull surface are within the builder's own tolerance (1e-9
// of the cloud size) of a face; 1e-8 absolute for clouds of size ~1.
constexpr double kInsideTol = 1e-8;

std::vector<Vec3> BoxCorners(const Vec3& h, const Vec3& offset = Vec3::Zero()) {
  std::vector<Vec3> pts;
  for (int i = 0; i < 8; ++i) {
    pts.push_back(offset + Vec3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
  }
  return pts;
}

// The hull is closed and consistent: Euler's formula, unit normals, every
// vertex on or under every face, every face's vertices on its plane, each
// edge between the two faces edge_faces names.
void ExpectWellFormed(const ConvexHull& hull, double tol) {
  EXPECT_EQ(static_cast<int>(hull.vertices.size()) - static_cast<int>(hull.edges.size()) +
                static_cast<int>(hull.faces.size()),
            2);
  for (const ConvexHull::Face& face : hull.faces) {
    EXPECT_NEAR(face.normal.norm(), 1.0, 1e-12);
    ASSERT_GE(face.vertices.size(), 3u);
    for (int v : face.vertices) EXPECT_NEAR(face.normal.dot(hull.vertices[v]), face.offset, tol);
    for (const Vec3& v : hull.vertices) EXPECT_LE(face.normal.dot(v) - face.offset, tol);
    // counter-clockwise from outside: the polygon's Newell normal agrees
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < face.vertices.size(); ++i) {
      n += hull.vertices[face.vertices[i]].cross(hull.vertices[face.vertices[(i + 1) % face.vertices.size()]]);
    }
    EXPECT_GT(n.dot(face.normal), 0.0);
  }
  // each edge lies in the loops of its two faces: u -> v in the first, v -> u in the second
  ASSERT_EQ(hull.edge_faces.size(), hull.edges.size());
  const auto has_directed = [&](int f, int u, int v) {
    const std::vector<int>& loop = hull.faces[f].vertices;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (loop[i] == u && loop[(i + 1) % loop.size()] == v) return true;
    }
    return false;
  };
  for (std::size_t e = 0; e < hull.edges.size(); ++e) {
    const int u = hull.edges[e][0], v = hull.edges[e][1];
    ASSERT_GE(hull.edge_faces[e][0], 0);
    ASSERT_GE(hull.edge_faces[e][1], 0);
    EXPECT_TRUE(has_directed(hull.edge_faces[e][0], u, v));
    EXPECT_TRUE(has_directed(hull.edge_faces[e][1], v, u));
  }
}

// Verifies that the hull of a box's corners plus interior points is the box:
// 8 vertices, 6 quads, 12 edges, with the analytic mass properties.
TEST(ConvexHullTest, BoxCornersWithInteriorPointsGiveTheBox) {
  const Vec3 h(0.5, 1.0, 1.5);
  std::vector<Vec3> pts = BoxCorners(h);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  for (int i = 0; i < 50; ++i) pts.push_back(Vec3{u(rng), u(rng), u(rng)});
  std::shared_ptr<const ConvexHull> hull;
  Vec3 centroid;
  ASSERT_TRUE(BuildConvexHull(pts, &hull, &centroid).ok());
  EXPECT_EQ(hull->vertices.size(), 8u);
  EXPECT_EQ(hull->faces.size(), 6u);
  EXPECT_EQ(hull->edges.size(), 12u);
  for (const auto& face : hull->faces) EXPECT_EQ(face.vertices.size(), 4u);
  ExpectWellFormed(*hull, 1e-12);
  EXPECT_LT(centroid.norm(), 1e-12);

  const double rho = 750.0;
  const double a = h.x(), b = h.y(), c = h.z();
  const double m = rho * 8 * a * b * c;
  EXPECT_NEAR(ConvexHullVolume(*hull), 8 * a * b * c, kMassRelTol * 8 * a * b * c);
  const MassProperties props = ConvexHullMassProperties(*hull, rho);
  EXPECT_NEAR(props.mass, m, kMassRelTol * m);
  const Vec3 expected(m / 3 * (b * b + c * c), m / 3 * (a * a + c * c), m / 3 * (a * a + b * b));
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double want = i == j ? expected[i] : 0.0;
      EXPECT_NEAR(props.inertia(i, j), want, kMassRelTol * expected.maxCoeff()) << i << "," << j;
    }
  }
}

// Verifies the unit tetrahedron: 4 triangles, 6 edges, volume 1/6, centroid
// at (1/4, 1/4, 1/4) and the textbook inertia about it.
TEST(ConvexHullTest, TetrahedronHasAnalyticMassProperties) {
  const std::vector<Vec3> pts = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  std::shared_ptr<const ConvexHull> hull;
  Vec3 centroid;
  ASSERT_TRUE(BuildConvexHull(pts, &hull, &centroid).ok());
  EXPECT_EQ(hull->vertices.size(), 4u);
  EXPECT_EQ(hull->faces.size(), 4u);
  EXPECT_EQ(hull->edges.size(), 6u);
  ExpectWellFormed(*hull, 1e-12);
  EXPECT_TRUE(centroid.isApprox(Vec3(0.25, 0.25, 0.25), 1e-14));
  EXPECT_NEAR(ConvexHullVolume(*hull), 1.0 / 6.0, kMassRelTol);
  // about the origin corner: I_xx = rho/60 * 2 (Tonon 2004, unit right
  // tetrahedron: integral of x^2 = 1/60, of xy = 1/120); shift to centroid
  const double m = 1.0 / 6.0;
  Mat3 c_origin;
  c_origin << 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120, 1.0 / 60;
  const Vec3 g(0.25, 0.25, 0.25);
  const Mat3 c_g = c_origin - m * g * g.transpose();
  const Mat3 expected = c_g.trace() * Mat3::Identity() - c_g;
  const MassProperties props = ConvexHullMassProperties(*hull, 1.0);
  EXPECT_NEAR(props.mass, m, kMassRelTol * m);
  EXPECT_TRUE(props.inertia.isApprox(expected, kMassRelTol)) << props.inertia << "\n" << expected;
}

// Verifies that a cube far from the origin is recentred at its centre, with
// the same mass properties as at the origin.
TEST(ConvexHullTest, OffsetCubeIsRecentredAtItsCentroid) {
  const Vec3 offset(100.0, -20.0, 3.5);
  std::shared_ptr<const ConvexHull> hull;
  Vec3 centroid;
  ASSERT_TRUE(BuildConvexHull(BoxCorners(Vec3(1, 1, 1), offset), &hull, &centroid).ok());
  EXPECT_TRUE(centroid.isApprox(offset, 1e-12));
  ExpectWellFormed(*hull, 1e-9);
  for (const Vec3& v : hull->vertices) EXPECT_NEAR(v.cwiseAbs().maxCoeff(), 1.0, 1e-12);
  const MassProperties props = ConvexHullMassProperties(*hull, 2.0);
  EXPECT_NEAR(props.mass, 16.0, kMassRelTol * 16.0);
  EXPECT_TRUE(props.inertia.isApprox(Mat3::Identity() * 16.0 / 3.0 * 2.0, kMassRelTol));
}

// Verifies the products of inertia: a box rotated by R has inertia
// R I_box R^T, full off-diagonal terms included.
TEST(ConvexHullTest, RotatedBoxHasRotatedInertia) {
  const Vec3 h(0.3, 0.7, 1.1);
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  std::vector<Vec3> pts;
  for (const Vec3& p : BoxCorners(h)) pts.push_back(R * p + Vec3(5, 6, 7));
  std::shared_ptr<const ConvexHull> hull;
  ASSERT_TRUE(BuildConvexHull(pts, &hull).ok());
  const double rho = 3.0, m = rho * 8 * h.prod();
  const Vec3 diag(m / 3 * (h.y() * h.y() + h.z() * h.z()), m / 3 * (h.x() * h.x() + h.z() * h.z()),
                  m / 3 * (h.x() * h.x() + h.y() * h.y()));
  const Mat3 expected = R * diag.asDiagonal() * R.transpose();
  const MassProperties props = ConvexHullMassProperties(*hull, rho);
  EXPECT_NEAR(props.mass, m, kMassRelTol * m);
  EXPECT_TRUE(props.inertia.isApprox(expected, kMassRelTol)) << props.inertia << "\n" << expected;
}

// Verifies that midpoints of box edges and faces do not become vertices.
TEST(ConvexHullTest, PointsOnEdgesAndFacesAreNotVertices) {
  std::vector<Vec3> pts;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z) pts.push_back(Vec3(x, y, z));
  std::shared_ptr<const ConvexHull> hull;
  ASSERT_TRUE(BuildConvexHull(pts, &hull).ok());
  EXPECT_EQ(hull->vertices.size(), 8u);
  EXPECT_EQ(hull->faces.size(), 6u);
  EXPECT_EQ(hull->edges.size(), 12u);
  ExpectWellFormed(*hull, 1e-12);
}

// Verifies that thousands of random points on a box's faces (plus its
// corners and duplicates) give the 8-vertex, 6-quad box at sizes from 1 mm to
// 1 km and 1 km from the origin: the tolerance scales with the cloud.
TEST(ConvexHullTest, BoxSurfaceSamplesGiveTheBoxAtAnyScale) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double scale : {1e-3, 1.0, 1e3}) {
    for (double offset : {0.0, 1e3}) {
      std::vector<Vec3> pts = BoxCorners(Vec3::Constant(scale), Vec3::Constant(offset));
      for (int i = 0; i < 2000; ++i) {
        Vec3 p{u(rng), u(rng), u(rng)};
        p[i % 3] = (i / 3) % 2 ? 1.0 : -1.0;  // onto a face
        pts.push_back(Vec3::Constant(offset) + scale * p);
      }
      pts.push_back(pts[0]);  // duplicate corner
      std::shared_ptr<const ConvexHull> hull;
      ASSERT_TRUE(BuildConvexHull(pts, &hull).ok()) << scale << " " << offset;
      EXPECT_EQ(hull->vertices.size(), 8u) << scale << " " << offset;
      EXPECT_EQ(hull->faces.size(), 6u) << scale << " " << offset;
      EXPECT_EQ(hull->edges.size(), 12u) << scale << " " << offset;
      const double volume = 8.0 * scale * scale * scale;
      EXPECT_NEAR(ConvexHullVolume(*hull), volume, kMassRelTol * volume) << scale << " " << offset;
    }
  }
}

// Verifies on random clouds that every input point is inside or on the hull
// and the topology is closed.
TEST(ConvexHullTest, RandomCloudsContainEveryPoint) {
  std::mt19937 rng(42);
  std::normal_distribution<double> gauss(0.0, 1.0);
  for (int n : {4, 5, 10, 100, 1000, 5000}) {
    std::vector<Vec3> pts;
    for (int i = 0; i < n; ++i) pts.push_back(Vec3{gauss(rng), gauss(rng), gauss(rng)});
    std::shared_ptr<const ConvexHull> hull;
    Vec3 centroid;
    ASSERT_TRUE(BuildConvexHull(pts, &hull, &centroid).ok()) << n;
    ExpectWellFormed(*hull, kInsideTol);
    for (const Vec3& p : pts) {
      for (const auto& face : hull->faces) ASSERT_LE(face.normal.dot(p - centroid) - face.offset, kInsideTol);
    }
    EXPECT_GT(ConvexHullVolume(*hull), 0.0);
  }
}

// Verifies clouds on a sphere (every point a vertex) and on a grid (many
// coplanar points) give closed hulls.
TEST(ConvexHullTest, SphereAndGridCloudsAreClosed) {
  std::mt19937 rng(3);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<Vec3> sphere;
  for (int i = 0; i < 500; ++i) sphere.push_back(Vec3{gauss(rng), gauss(rng), gauss(rng)}.normalized());
  std::shared_ptr<const ConvexHull> hull;
  ASSERT_TRUE(BuildConvexHull(sphere, &hull).ok());
  EXPECT_EQ(hull->vertices.size(), 500u);
  ExpectWellFormed(*hull, kInsideTol);
  std::vector<Vec3> grid;
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 5; ++y)
      for (int z = 0; z < 4; ++z) grid.push_back(Vec3(0.1 * x, 0.2 * y, 0.3 * z));
  ASSERT_TRUE(BuildConvexHull(grid, &hull).ok());
  EXPECT_EQ(hull->vertices.size(), 8u);
  EXPECT_EQ(hull->faces.size(), 6u);
  ExpectWellFormed(*hull, kInsideTol);
  EXPECT_NEAR(ConvexHullVolume(*hull), 0.5 * 0.8 * 0.9, kMassRelTol);
}

// Verifies the error messages for too few, non-finite and coplanar points.
TEST(ConvexHullTest, BadInputFailsWithAMessage) {
  std::shared_ptr<const ConvexHull> hull;
  Status s = BuildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, &hull);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "convex hull needs at least 4 points, got 3");

  s = BuildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, 0)}, &hull);
  EXPECT_TRUE(s.ok());
  s = BuildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::nan(""), 0), Vec3(0, 0, 1)}, &hull);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("point 2 is not finite"), std::string::npos) << s.message();

  s = BuildConvexHull({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(0.5, 0.2, 0)}, &hull);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("points are coplanar"), std::string::npos) << s.message();

  s = BuildConvexHull({Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2), Vec3(3, 3, 3)}, &hull);
  EXPECT_NE(s.message().find("collinear"), std::string::npos) << s.message();

  hull.reset();
  s = BuildConvexHull({Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)}, &hull);
  EXPECT_NE(s.message().find("coincide"), std::string::npos) << s.message();
  EXPECT_EQ(hull, nullptr);  // untouched on failure
}

}  // namespace
}  // namespace contactsim
