#include "service/physics/cylinder_hull.h"

#include <algorithm>
#include <cmath>

#include "service/physics/validation.h"

namespace contactsim {

int CylinderSides(double relative_error) {
  if (!(relative_error > 0.0 && relative_error < 1.0)) return 3;
  // sagitta r (1 - cos(pi / n)) <= e r
  const double n = std::ceil(kPi / std::acos(1.0 - relative_error) - 1e-9);
  return static_cast<int>(std::clamp(n, 3.0, static_cast<double>(kMaxCylinderSides)));
}

std::vector<Vec3> CylinderPoints(double radius, double length, int sides) {
  std::vector<Vec3> points;
  points.reserve(2 * sides);
  for (int k = 0; k < sides; ++k) {
    const double angle = 2.0 * kPi * k / sides;
    const double x = radius * std::cos(angle), y = radius * std::sin(angle);
    points.emplace_back(x, y, -0.5 * length);
    points.emplace_back(x, y, 0.5 * length);
  }
  return points;
}

Status BuildCylinderHull(double radius, double length, std::shared_ptr<const ConvexHull>* hull,
                         double relative_error) {
  Status st;
  if (!(st = CheckPositive("radius", radius)).ok()) return st;
  if (!(st = CheckPositive("length", length)).ok()) return st;
  return BuildConvexHull(CylinderPoints(radius, length, CylinderSides(relative_error)), hull);
}

}  // namespace contactsim
