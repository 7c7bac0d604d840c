#include "service/collision/manifold_reduction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "service/collision/narrowphase.h"
#include "tests/collision/narrowphase_test_util.h"

namespace contactsim {
namespace {

// Areas of unit-size polygons: round-off only.
using testing_util::kTol;

double QuadArea(const ContactSet& c) {
  // shoelace on the xy projection, for a convex quad in any vertex order the
  // largest of the three possible orderings is the convex one
  auto area = [&](int i, int j, int k, int l) {
    const Vec3 p[4] = {c[i].point, c[j].point, c[k].point, c[l].point};
    double s = 0.0;
    for (int m = 0; m < 4; ++m) s += p[m].x() * p[(m + 1) % 4].y() - p[(m + 1) % 4].x() * p[m].y();
    return std::abs(0.5 * s);
  };
  return std::max({area(0, 1, 2, 3), area(0, 1, 3, 2), area(0, 2, 1, 3)});
}

// Verifies that eight points of a regular octagon reduce to four that keep the
// deepest point and span the largest inscribed quadrilateral (a square, 2 R^2).
TEST(ManifoldReductionTest, OctagonReducesToLargestSquareWithDeepestPoint) {
  ContactSet contacts(1);  // an unrelated contact before the manifold stays
  for (int k = 0; k < 8; ++k) {
    Contact c;
    c.point = Vec3(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4), 0);
    c.normal = Vec3::UnitZ();
    c.depth = k == 3 ? 0.02 : 0.01;
    c.feature_id = k;
    contacts.push_back(c);
  }
  ReduceManifold(1, &contacts);
  ASSERT_EQ(contacts.size(), 5u);
  const ContactSet kept(contacts.begin() + 1, contacts.end());
  EXPECT_NEAR(QuadArea(kept), 2.0, kTol);
  bool has_deepest = false;
  for (const Contact& c : kept) has_deepest = has_deepest || c.feature_id == 3;
  EXPECT_TRUE(has_deepest);
}

// Verifies that four or fewer points are left as they are.
TEST(ManifoldReductionTest, FourPointsAreKept) {
  ContactSet contacts(4);
  for (int k = 0; k < 4; ++k) contacts[k].feature_id = k;
  ReduceManifold(0, &contacts);
  ASSERT_EQ(contacts.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(contacts[k].feature_id, static_cast<uint32_t>(k));
}

// Verifies that an octagonal prism resting on the ground gives four well-spread points.
TEST(ManifoldReductionTest, OctagonalPrismOnPlaneGivesFourPoints) {
  std::vector<Vec3> points;
  for (int k = 0; k < 8; ++k) {
    for (double z : {-0.2, 0.2}) points.emplace_back(0.5 * std::cos(k * M_PI / 4), 0.5 * std::sin(k * M_PI / 4), z);
  }
  ContactSet out;
  ASSERT_EQ(Collide(testing_util::Convex(1, testing_util::Hull(points), Vec3(0, 0, 0.19)), 0,
                    testing_util::Ground(2), 1, 0.0, &out),
            4);
  EXPECT_NEAR(QuadArea(out), 2.0 * 0.25, kTol);
}

// Verifies that a manifold of more points than the reduction keeps on its
// stack (100 points of a regular polygon, a hull face's worth) reduces the
// same way: the deepest point and the largest inscribed square (2 R^2).
TEST(ManifoldReductionTest, HundredPointPolygonReducesToLargestSquare) {
  ContactSet contacts;
  for (int k = 0; k < 100; ++k) {
    Contact c;
    c.point = Vec3(std::cos(k * M_PI / 50), std::sin(k * M_PI / 50), 0);
    c.normal = Vec3::UnitZ();
    c.depth = k == 7 ? 0.02 : 0.01;
    c.feature_id = k;
    contacts.push_back(c);
  }
  ReduceManifold(0, &contacts);
  ASSERT_EQ(contacts.size(), 4u);
  EXPECT_NEAR(QuadArea(contacts), 2.0, kTol);
  EXPECT_EQ(contacts[0].feature_id, 7u);  // the points keep their order
}

// A manifold along `normal` (unit, from A to B) built in a frame whose z
// is -normal: local (x, y) is the in-plane position, local z the height
// above the deepest level, so depth = top_depth - z. Scaled by `scale`.
struct ManifoldFrame {
  Vec3 normal;
  Mat3 R;  // columns: local x, y, z in the world
  Vec3 origin;
  double scale;
  double top_depth;

  Contact Point(double x, double y, double z, uint32_t id) const {
    Contact c;
    c.point = origin + scale * R * Vec3(x, y, z);
    c.normal = normal;
    c.depth = top_depth - scale * z;
    c.feature_id = id;
    return c;
  }
};

ManifoldFrame RandomFrame(std::mt19937_64& rng, double scale) {
  const Quat q = testing_util::RandomRotation(rng);
  ManifoldFrame f;
  f.R = q.toRotationMatrix();
  f.normal = -f.R.col(2);
  f.origin = testing_util::RandomVector(rng, 10.0 * scale);
  f.scale = scale;
  f.top_depth = std::uniform_real_distribution<double>(-0.1, 0.1)(rng) * scale;
  return f;
}

bool AllBelow(const ContactSet& c, uint32_t id_end) {
  return std::all_of(c.begin(), c.end(), [&](const Contact& k) { return k.feature_id < id_end; });
}

bool Has(const ContactSet& c, uint32_t id) {
  return std::any_of(c.begin(), c.end(), [&](const Contact& k) { return k.feature_id == id; });
}

// The scales and orientations the reduction is swept over: 1 mm to 1 m.
constexpr double kScales[] = {1e-3, 1e-2, 0.1, 1.0};
constexpr int kPoses = 25;

// Verifies that a face of 3 to 8 corners level with the deepest point (a
// regular polygon of random size and phase, tilted less than the flush
// slope) keeps its corners when its neighbours' vertices lie above it
// within the margin, farther out than the face (the widest area alone took
// them over the face's corners): at every scale and orientation, every kept
// point is a corner, the deepest among them, min(corners, 4) in all.
TEST(ManifoldReductionTest, FaceLevelWithTheDeepestPointKeepsItsCorners) {
  std::mt19937_64 rng(39);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double scale : kScales) {
    for (int pose = 0; pose < kPoses; ++pose) {
      const ManifoldFrame f = RandomFrame(rng, scale);
      const int corners = 3 + pose % 6;
      const double phase = 2.0 * M_PI * u(rng), radius = 0.3 + 0.7 * u(rng);
      // a tilt below the flush slope along a random direction
      const double tilt = 0.9 * kFlushSlope * u(rng), dir = 2.0 * M_PI * u(rng);
      ContactSet contacts;
      double lowest = 0.0;
      for (int k = 0; k < corners; ++k) {
        const double a = phase + 2.0 * M_PI * k / corners;
        const double x = radius * std::cos(a), y = radius * std::sin(a);
        const double z = tilt * (x * std::cos(dir) + y * std::sin(dir));
        lowest = std::min(lowest, z);
        contacts.push_back(f.Point(x, y, z, static_cast<uint32_t>(k)));
      }
      // vertices of the neighbour faces: up to twice the face's reach out,
      // rising at 10 to 40 degrees from its rim
      for (int k = 0; k < 6; ++k) {
        const double a = 2.0 * M_PI * u(rng), r = radius * (1.0 + u(rng));
        const double rise = std::tan((10.0 + 30.0 * u(rng)) * M_PI / 180.0) * (r - radius + 0.05);
        contacts.push_back(f.Point(r * std::cos(a), r * std::sin(a), rise + tilt * r, 100u + k));
      }
      int deepest = 0;
      for (int k = 1; k < corners; ++k) {
        if (contacts[k].depth > contacts[deepest].depth) deepest = k;
      }
      ReduceManifold(0, &contacts);
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " pose " << pose << " corners " << corners);
      EXPECT_EQ(contacts.size(), std::min<size_t>(corners, kMaxManifoldPoints));
      EXPECT_TRUE(AllBelow(contacts, 100u));
      EXPECT_TRUE(Has(contacts, static_cast<uint32_t>(deepest)));
    }
  }
}

// Verifies that a convex hull landing flat on a triangle face, its
// neighbours' vertices 5 to 15 mm above within the margin (the 30-point
// hull of tests/contact/resting_hull_scenarios_test.cpp, seed 3, in its
// landing step), gets the triangle's three corners from the detector.
TEST(ManifoldReductionTest, HullLandingOnATriangleKeepsTheTriangle) {
  // the landing step's seven points, in-plane offsets from the deepest (m)
  // and heights above it (m)
  const double kPoints[7][3] = {{0.001520, 0.069886, 0.0},    {0.0, 0.0, 0.0},
                                {-0.060024, -0.007467, 0.013841}, {0.029174, 0.022211, 0.011627},
                                {-0.044684, -0.019984, 0.011584}, {-0.049984, 0.021423, 0.0},
                                {0.020081, 0.008332, 0.003487}};
  std::vector<Vec3> vertices;
  for (const auto& p : kPoints) vertices.emplace_back(p[0], p[1], p[2]);
  vertices.emplace_back(0.0, 0.01, 0.05);  // a top, out of reach
  const std::shared_ptr<const ConvexHull> hull = testing_util::Hull(vertices);
  double low = 0.0;
  for (const Vec3& v : hull->vertices) low = std::min(low, v.z());
  const double gap = 0.0016;  // m, the face above the ground
  ContactSet out;
  ASSERT_EQ(Collide(testing_util::Convex(1, hull, Vec3(0, 0, gap - low)), 0, testing_util::Ground(2), 1, 0.02, &out),
            3);
  for (const Contact& c : out) EXPECT_NEAR(c.depth, -gap, kTol);
}

// Verifies that a long narrow flat (a 71-sided wheel's: 8.85 x 50 mm at
// 0.1 m, its neighbour flats rising at 2 pi / 71) keeps its four corners,
// though a neighbour's far vertex seen from the flat's far corner rises
// less than the flush slope, at 1 mm to 1 m.
TEST(ManifoldReductionTest, LongNarrowFlatKeepsItsFourCorners) {
  const double w = 0.0885, l = 0.5, a = 2.0 * M_PI / 71.0;  // in units of the scale
  for (const double scale : kScales) {
    std::mt19937_64 rng(71);
    const ManifoldFrame f = RandomFrame(rng, scale);
    ContactSet contacts;
    uint32_t id = 0;
    for (const double y : {-0.5 * l, 0.5 * l}) {
      for (const double side : {-1.0, 1.0}) {
        contacts.push_back(f.Point(side * 0.5 * w, y, 0.0, id++));                                    // corners 0-3
        contacts.push_back(f.Point(side * (0.5 * w + w * std::cos(a)), y, w * std::sin(a), 100u + id));  // neighbours
      }
    }
    ReduceManifold(0, &contacts);
    SCOPED_TRACE(::testing::Message() << "scale " << scale);
    ASSERT_EQ(contacts.size(), 4u);
    EXPECT_TRUE(AllBelow(contacts, 100u));
  }
}

// Verifies that a thin plate (0.5 x 0.5 x 0.02 m) whose top face lies within
// the margin rests on its four bottom corners, flat and tilted 0.01 to
// 0.3 rad about a random horizontal axis, at 1 mm to 1 m.
TEST(ManifoldReductionTest, ThinPlateKeepsItsBottomCorners) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double scale : kScales) {
    for (const double tilt : {0.0, 0.01, 0.05, 0.3}) {
      const double a = 2.0 * M_PI * u(rng);
      const Quat q(Eigen::AngleAxisd(tilt, Vec3(std::cos(a), std::sin(a), 0.0)));
      const Vec3 h = scale * Vec3(0.25, 0.25, 0.01);
      const RigidBody plate = testing_util::Box(1, h, Vec3::Zero(), q);
      // lowest corner 0.1 h_z into the ground, the margin past the top face
      double low = 0.0;
      for (int k = 0; k < 8; ++k) {
        const Vec3 corner((k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z());
        low = std::min(low, (q * corner).z());
      }
      const RigidBody placed = testing_util::Box(1, h, Vec3(0, 0, -low - 0.1 * h.z()), q);
      ContactSet out;
      Collide(placed, 0, testing_util::Ground(2), 1, scale, &out);
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " tilt " << tilt);
      ASSERT_EQ(out.size(), 4u);
      for (const Contact& c : out) {
        const Vec3 local = q.conjugate() * (c.point + 0.5 * c.depth * Vec3::UnitZ() - placed.x);
        EXPECT_LT(local.z(), 0.0) << "a top corner was kept";
      }
    }
  }
}

// Verifies that a face tilted past the flush slope (0.05 and 0.5, an
// octagon of radius 1 whose vertex 3 is deepest) reduces as Gregorius's
// four points: the deepest and the largest inscribed square, 2 R^2.
TEST(ManifoldReductionTest, FaceTiltedPastTheFlushSlopeKeepsTheWidestSquare) {
  for (const double slope : {2.5 * kFlushSlope, 0.5}) {
    ContactSet contacts;
    for (int k = 0; k < 8; ++k) {
      Contact c;
      c.point = Vec3(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4), 0);
      c.normal = Vec3::UnitZ();
      c.depth = 0.1 + slope * c.point.dot(Vec3(std::cos(3 * M_PI / 4), std::sin(3 * M_PI / 4), 0));
      c.feature_id = k;
      contacts.push_back(c);
    }
    ReduceManifold(0, &contacts);
    ASSERT_EQ(contacts.size(), 4u);
    EXPECT_NEAR(QuadArea(contacts), 2.0, kTol);
    EXPECT_TRUE(Has(contacts, 3u));
  }
}

// Verifies that the reduction of random point sets (8 to 40 points within
// the margin, depths from 0.05 in to 0.05 out, some sets with a level face)
// picks the same points at every scale from 1 mm to 1 m and in every
// orientation, and always the deepest: its rules are ratios.
TEST(ManifoldReductionTest, RandomSetsReduceAlikeAtEveryScaleAndOrientation) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int set = 0; set < 200; ++set) {
    const int n = 8 + set % 33;
    std::vector<Vec3> local;
    for (int k = 0; k < n; ++k) {
      // a third of the sets put their first four points on one level
      const bool level = set % 3 == 0 && k < 4;
      local.emplace_back(u(rng), u(rng), level ? 0.0 : 0.05 + 0.05 * u(rng));
    }
    std::vector<uint32_t> reference;
    for (const double scale : kScales) {
      for (int pose = 0; pose < 4; ++pose) {
        const ManifoldFrame f = RandomFrame(rng, scale);
        ContactSet contacts;
        for (int k = 0; k < n; ++k) contacts.push_back(f.Point(local[k].x(), local[k].y(), local[k].z(), k));
        const uint32_t deepest = static_cast<uint32_t>(
            std::max_element(local.begin(), local.end(), [](const Vec3& a, const Vec3& b) { return a.z() > b.z(); }) -
            local.begin());
        ReduceManifold(0, &contacts);
        std::vector<uint32_t> ids;
        for (const Contact& c : contacts) ids.push_back(c.feature_id);
        SCOPED_TRACE(::testing::Message() << "set " << set << " scale " << scale << " pose " << pose);
        EXPECT_LE(ids.size(), kMaxManifoldPoints);
        EXPECT_TRUE(Has(contacts, deepest));
        if (reference.empty()) reference = ids;
        EXPECT_EQ(ids, reference);
      }
    }
  }
}

}  // namespace
}  // namespace contactsim
