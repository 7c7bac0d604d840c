// The patch geometry of torsional friction (service/contact/patch_torsion.h)
// against closed forms: the mean distance of a patch's area from its
// centroid, and where the friction of each of its points acts.
#include "service/contact/patch_torsion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace contactsim {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Verifies r_eff = L (sqrt(2) + ln(1 + sqrt(2))) / 6 for squares of side L
// in any plane and any order of their corners, and the rectangle's
// [2 a b d + a^3 asinh(b / a) + b^3 asinh(a / b)] / (6 a b).
TEST(PatchTorsion, SquareAndRectangleHaveTheirClosedFormRadius) {
  const Vec3 n = Vec3(1, 2, 3).normalized();
  Vec3 t1, t2;
  PerpendicularBasis(n, &t1, &t2);
  for (double a : {0.01, 0.1, 2.0}) {
    for (double b : {a, 3 * a}) {
      const Vec3 o(0.3, -1, 2);
      // corners out of order, the patch's centroid off the origin
      const Vec3 corners[4] = {o + a * t1 + b * t2, o - a * t1 - b * t2, o - a * t1 + b * t2, o + a * t1 - b * t2};
      Vec3 centroid;
      const double r = UniformPatchRadius(corners, 4, n, &centroid);
      const double d = std::hypot(a, b);
      const double expected =
          (2 * a * b * d + a * a * a * std::asinh(b / a) + b * b * b * std::asinh(a / b)) / (6 * a * b);
      EXPECT_NEAR(r, expected, 1e-12 * expected) << a << " x " << b;
      EXPECT_NEAR((centroid - o).norm(), 0.0, 1e-12 * a);
      if (a == b) {
        EXPECT_NEAR(r / (2 * a), (std::sqrt(2.0) + std::log(1 + std::sqrt(2.0))) / 6, 1e-12);
      }
    }
  }
}

// Verifies a disc's 2 R / 3, approached by regular polygons: 256 sides
// within 1e-4 of it.
TEST(PatchTorsion, RegularPolygonApproachesTheDiscsTwoThirdsRadius) {
  const double R = 0.3;
  std::vector<Vec3> polygon;
  for (int k = 0; k < 256; ++k) polygon.push_back(R * Vec3(std::cos(2 * kPi * k / 256), std::sin(2 * kPi * k / 256), 0));
  Vec3 centroid;
  const double r = UniformPatchRadius(polygon.data(), static_cast<int>(polygon.size()), Vec3::UnitZ(), &centroid);
  EXPECT_NEAR(r / R, 2.0 / 3.0, 1e-4);
}

// Verifies the degenerate patches: one point, two, and three on a line have
// no area and keep their friction where they are.
TEST(PatchTorsion, PointsAndLinesHaveNoPatch) {
  const Vec3 line[3] = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  Vec3 centroid;
  for (int count : {1, 2, 3}) EXPECT_EQ(UniformPatchRadius(line, count, Vec3::UnitZ(), &centroid), 0.0) << count;
  ContactSet contacts(2);
  contacts[0].point = Vec3(-1, 0, 0);
  contacts[1].point = Vec3(1, 0, 0);
  for (Contact& c : contacts) c.a = 0, c.b = 1;
  std::vector<Vec3> points;
  PatchFrictionPoints(contacts, &points);
  EXPECT_EQ(points[0], contacts[0].point);
  EXPECT_EQ(points[1], contacts[1].point);
}

// Verifies that a square face's four corners act at r_eff from its centre
// (in the plane, keeping each corner's height along n), and that a second
// pair's patch is taken apart from the first.
TEST(PatchTorsion, FaceCornersMoveToTheEffectiveRadius) {
  const double a = 0.1, r_eff = 2 * a * (std::sqrt(2.0) + std::log(1 + std::sqrt(2.0))) / 6;
  ContactSet contacts;
  for (int pair : {0, 1}) {
    for (const Vec3& corner : {Vec3(a, a, 0), Vec3(-a, a, 0), Vec3(-a, -a, 0), Vec3(a, -a, 0)}) {
      Contact c;
      c.a = 0;
      c.b = 1 + pair;
      c.point = corner + Vec3(5 * pair, 0, 1e-3 * (corner.x() > 0));
      contacts.push_back(c);
    }
  }
  std::vector<Vec3> points;
  PatchFrictionPoints(contacts, &points);
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Vec3 centre(k < 4 ? 0.0 : 5.0, 0.0, 0.0);
    const Vec3 d = points[k] - centre;
    EXPECT_NEAR(std::hypot(d.x(), d.y()), r_eff, 1e-12) << k;
    EXPECT_EQ(points[k].z(), contacts[k].point.z()) << k;
  }
}

}  // namespace
}  // namespace contactsim
