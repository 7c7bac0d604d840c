#include "service/collision/manifold_reduction.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace contactsim
