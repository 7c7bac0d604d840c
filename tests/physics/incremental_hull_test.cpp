#include "service/physics/incremental_hull.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "service/physics/quickhull.h"
#include "tests/physics/point_clouds.h"

namespace contactsim {
namespace {

// A box's surface sampled on a grid: many coplanar points, the case where
// the cone step meets faces that a new point sees only within the
// tolerance.
std::vector<Vec3> BoxGrid(int n, const Vec3& half) {
  std::vector<Vec3> pts;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      for (int k = 0; k <= n; ++k) {
        if (i != 0 && i != n && j != 0 && j != n && k != 0 && k != n) continue;
        pts.emplace_back(half.x() * (2.0 * i / n - 1.0), half.y() * (2.0 * j / n - 1.0),
                         half.z() * (2.0 * k / n - 1.0));
      }
    }
  }
  return pts;
}

// `pts` moved at random by up to `times` the hull tolerance along each
// axis: faces flat only within a few tolerances, where the points a new
// point sees within the tolerance decide the cone.
std::vector<Vec3> Jittered(std::vector<Vec3> pts, double times) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double step = times * HullTolerance(pts);
  for (Vec3& p : pts) p += step * Vec3(u(rng), u(rng), u(rng));
  return pts;
}

// Every point's height above the hull of `added`, from scratch: qhull's
// triangles and a scan of their planes (the greedy rule as docs/models.md
// states it), slivers left out.
std::vector<double> HeightsFromScratch(const std::vector<Vec3>& pts, const std::vector<int>& added, double tol) {
  std::vector<Vec3> kept;
  for (int i : added) kept.push_back(pts[i]);
  std::vector<std::array<int, 3>> tris;
  EXPECT_TRUE(Quickhull(kept, tol, &tris).ok());
  std::vector<double> h(pts.size(), -1e300);
  for (size_t p = 0; p < pts.size(); ++p) {
    if (std::find(added.begin(), added.end(), static_cast<int>(p)) != added.end()) continue;
    for (const auto& t : tris) {
      const Vec3 n = (kept[t[1]] - kept[t[0]]).cross(kept[t[2]] - kept[t[0]]);
      // a sliver's plane (area below 1e-6 of its longest edge squared) is
      // set by round-off: qhull leaves some inside facets it merged
      const double edge2 = std::max({(kept[t[1]] - kept[t[0]]).squaredNorm(), (kept[t[2]] - kept[t[1]]).squaredNorm(),
                                     (kept[t[0]] - kept[t[2]]).squaredNorm()});
      if (n.norm() > 1e-6 * edge2) h[p] = std::max(h[p], n.dot(pts[p] - kept[t[0]]) / n.norm());
    }
  }
  return h;
}

// Verifies that, round after round, the point the grown hull names as the
// highest is the highest above the hull of the points added so far built
// from scratch (within a few tolerances: equal heights may name another
// point of the same height, and qhull's planes are a few tolerances off),
// and that it stops only when no point is above that hull by more than
// noise: on ellipsoids (every point a vertex), a random cloud, box grids
// (many coplanar points) and box grids jittered by a few tolerances.
TEST(IncrementalHullTest, NamesTheHighestPointAsAHullFromScratchDoes) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<Vec3> random;
  for (int i = 0; i < 300; ++i) random.push_back(Vec3(g(rng), 0.3 * g(rng), 2.0 * g(rng)));
  const std::vector<std::vector<Vec3>> clouds = {EllipsoidPoints(400, Vec3(1.0, 1.0, 1.0)),
                                                 EllipsoidPoints(300, Vec3(0.05, 0.08, 0.2)), random,
                                                 BoxGrid(6, Vec3(0.1, 0.2, 0.3)), BoxGrid(3, Vec3(1.0, 1.0, 1.0)),
                                                 Jittered(BoxGrid(8, Vec3(0.1, 0.2, 0.3)), 2.0),
                                                 Jittered(BoxGrid(8, Vec3(0.1, 0.2, 0.3)), 5.0)};
  for (size_t c = 0; c < clouds.size(); ++c) {
    const std::vector<Vec3>& pts = clouds[c];
    const double tol = HullTolerance(pts);
    // the height of a point above a face flat only within the tolerance
    // depends on which of its triangles measures it (qhull merges facets
    // whose centrums lie within the tolerance of their neighbours' planes):
    // a few tolerances (measured: the very same highest point on every
    // cloud while the highest is above the noise)
    const double slack = 8.0 * tol;
    // on the jittered grids, once every corner is in, every height is
    // noise (measured: up to 1e-7, 2e-7 of the grid's size): the choice
    // among the noise is not compared
    const double noise = 1e-6;
    std::array<int, 4> corners;
    ASSERT_TRUE(InitialTetrahedron(pts, tol, &corners).ok());
    IncrementalHull hull(pts, tol);
    hull.Start(corners);
    std::vector<int> added(corners.begin(), corners.end());
    for (int round = 0; round < 80; ++round) {
      const std::vector<double> h = HeightsFromScratch(pts, added, tol);
      const double top = *std::max_element(h.begin(), h.end());
      const int eye = hull.Highest();
      if (eye < 0) {
        EXPECT_LE(top, noise) << "cloud " << c << ", round " << round;
        break;
      }
      if (top > noise) {
        EXPECT_NEAR(h[eye], top, slack) << "cloud " << c << ", round " << round;
      } else {
        EXPECT_LE(h[eye], noise) << "cloud " << c << ", round " << round;
      }
      ASSERT_TRUE(hull.Add(eye).ok());
      added.push_back(eye);
    }
  }
}

// Verifies that a cloud of points in general position grows by cones
// alone, with no rebuild by qhull.
TEST(IncrementalHullTest, GrowsAnEllipsoidWithoutRebuilding) {
  const std::vector<Vec3> pts = EllipsoidPoints(600, Vec3(3.0, 0.5, 1.0));
  const double tol = HullTolerance(pts);
  std::array<int, 4> corners;
  ASSERT_TRUE(InitialTetrahedron(pts, tol, &corners).ok());
  IncrementalHull hull(pts, tol);
  hull.Start(corners);
  for (int round = 0; round < 200; ++round) {
    const int eye = hull.Highest();
    ASSERT_GE(eye, 0);
    ASSERT_TRUE(hull.Add(eye).ok());
  }
  EXPECT_EQ(hull.rebuilds(), 0);
}

}  // namespace
}  // namespace contactsim
