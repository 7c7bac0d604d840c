// Tests of mass properties against closed forms.
#include "service/physics/mass_properties.h"

#include <gtest/gtest.h>

#include <cmath>

#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

constexpr double kRelTol = 1e-12;  // closed forms: only round-off

// Verifies sphere mass and inertia: m = 4/3 pi r^3 rho, I = 2/5 m r^2.
TEST(MassProperties, SphereMatchesClosedForm) {
  const double r = 0.3, rho = 800.0;
  const MassProperties mp = ComputeMassProperties(Shape::Sphere(r), rho);
  const double m = 4.0 / 3.0 * kPi * r * r * r * rho;
  EXPECT_NEAR(mp.mass, m, kRelTol * m);
  EXPECT_TRUE(mp.inertia.isApprox(Mat3::Identity() * 0.4 * m * r * r, kRelTol));
}

// Verifies box inertia: I_xx = m (b^2 + c^2) / 3 for half extents (a, b, c).
TEST(MassProperties, BoxMatchesClosedForm) {
  const Vec3 h(0.1, 0.2, 0.3);
  const double rho = 1000.0;
  const MassProperties mp = ComputeMassProperties(Shape::Box(h), rho);
  const double m = 8.0 * h.prod() * rho;
  EXPECT_NEAR(mp.mass, m, kRelTol * m);
  EXPECT_NEAR(mp.inertia(0, 0), m * (h.y() * h.y() + h.z() * h.z()) / 3.0, kRelTol * m);
  EXPECT_NEAR(mp.inertia(1, 1), m * (h.x() * h.x() + h.z() * h.z()) / 3.0, kRelTol * m);
  EXPECT_NEAR(mp.inertia(2, 2), m * (h.x() * h.x() + h.y() * h.y()) / 3.0, kRelTol * m);
}

// Verifies the capsule against its two limits: zero length is a sphere, and
// the axial moment is a cylinder's plus a sphere's, m r^2 / 2 + 2/5 m r^2.
TEST(MassProperties, CapsuleMatchesClosedForms) {
  const double r = 0.2, rho = 500.0;
  const MassProperties ball = ComputeMassProperties(Shape::Capsule(r, 0.0), rho);
  const MassProperties sphere = ComputeMassProperties(Shape::Sphere(r), rho);
  EXPECT_NEAR(ball.mass, sphere.mass, kRelTol * sphere.mass);
  EXPECT_TRUE(ball.inertia.isApprox(sphere.inertia, 1e-12));

  const double h = 0.5;
  const MassProperties cap = ComputeMassProperties(Shape::Capsule(r, h), rho);
  const double m_cyl = rho * kPi * r * r * 2 * h, m_sph = rho * 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(cap.mass, m_cyl + m_sph, kRelTol * cap.mass);
  EXPECT_NEAR(cap.inertia(2, 2), m_cyl * r * r / 2 + 0.4 * m_sph * r * r, kRelTol * cap.mass);
  // transverse moment from an independent slicing integral (1e-6: quadrature)
  const int n = 20000;
  double ixx = 0.0;
  const double half_total = h + r;
  for (int i = 0; i < n; ++i) {
    const double z = -half_total + (i + 0.5) * 2 * half_total / n;
    const double dz = 2 * half_total / n;
    const double cap_z = std::max(0.0, std::abs(z) - h);
    const double rr = std::sqrt(std::max(0.0, r * r - cap_z * cap_z));
    const double dm = rho * kPi * rr * rr * dz;
    ixx += dm * (rr * rr / 4 + z * z);  // thin disk about a diameter, shifted
  }
  EXPECT_NEAR(cap.inertia(0, 0), ixx, 1e-6 * ixx);
}

// Verifies that the polyhedral integrals of a box's hull equal the analytic box.
TEST(MassProperties, BoxHullMatchesAnalyticBox) {
  const Vec3 h(0.3, 0.2, 0.1);
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  std::shared_ptr<const ConvexHull> hull;
  ASSERT_TRUE(BuildConvexHull(corners, &hull).ok());
  const MassProperties a = ComputeMassProperties(Shape::Convex(hull), 700.0);
  const MassProperties b = ComputeMassProperties(Shape::Box(h), 700.0);
  EXPECT_NEAR(a.mass, b.mass, 1e-9 * b.mass);
  EXPECT_TRUE(a.inertia.isApprox(b.inertia, 1e-9));
}

}  // namespace
}  // namespace contactsim
