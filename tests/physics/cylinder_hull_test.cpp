// Tests of the cylinder hull (cylinder_hull.h) against its closed forms.
#include "service/physics/cylinder_hull.h"

#include <gtest/gtest.h>

#include <cmath>

namespace contactsim {
namespace {

// Verifies the side count from the sagitta bound: 71 sides for 0.1% of the
// radius, and every count the least that meets its bound.
TEST(CylinderHull, SidesAreTheFewestWithinTheRadialError) {
  EXPECT_EQ(CylinderSides(), 71);
  for (const double e : {1e-1, 1e-2, 1e-3, 1e-4}) {
    const int n = CylinderSides(e);
    EXPECT_LE(1.0 - std::cos(kPi / n), e);
    EXPECT_GT(1.0 - std::cos(kPi / (n - 1)), e);
  }
  EXPECT_EQ(CylinderSides(1e-9), kMaxCylinderSides);
}

// Verifies the hull of a wheel: 2n vertices on the end circles, n + 2
// faces, every side's midpoint within 0.1% of the radius of the circle, the
// volume of the inscribed prism n/2 r^2 sin(2 pi / n) L, centred.
TEST(CylinderHull, WheelHullIsTheInscribedPrism) {
  const double r = 0.1, length = 0.04;
  std::shared_ptr<const ConvexHull> hull;
  ASSERT_TRUE(BuildCylinderHull(r, length, &hull).ok());
  const int n = CylinderSides();
  EXPECT_EQ(hull->vertices.size(), static_cast<size_t>(2 * n));
  EXPECT_EQ(hull->faces.size(), static_cast<size_t>(n + 2));
  double worst = 0.0;
  for (const ConvexHull::Face& f : hull->faces) {
    if (std::abs(f.normal.z()) > 0.5) continue;  // an end cap
    worst = std::max(worst, r - f.offset);       // a side's distance from the axis
  }
  EXPECT_LE(worst, 1e-3 * r + 1e-15);
  EXPECT_GT(worst, 0.5e-3 * r);
  EXPECT_NEAR(ConvexHullVolume(*hull), 0.5 * n * r * r * std::sin(2 * kPi / n) * length, 1e-15);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : hull->vertices) centre += v;
  EXPECT_LT(centre.norm() / hull->vertices.size(), 1e-15);
}

// Verifies bad sizes are refused naming the field.
TEST(CylinderHull, BadSizesAreRefused) {
  std::shared_ptr<const ConvexHull> hull;
  EXPECT_NE(BuildCylinderHull(-1.0, 1.0, &hull).message().find("radius"), std::string::npos);
  EXPECT_NE(BuildCylinderHull(1.0, std::nan(""), &hull).message().find("length"), std::string::npos);
  EXPECT_EQ(hull, nullptr);
}

}  // namespace
}  // namespace contactsim
