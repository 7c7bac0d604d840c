// A cylinder as a convex hull (body_settings.h's convex shape, or a
// compound's part): two regular n-gons inscribed in the end circles. The
// narrowphase has no cylinder of its own; a polygon fine enough stands in
// for it, as PyBullet's default mesh cylinder and MuJoCo's mesh collisions
// do.
//
// The number of sides comes from a bound on the radial error: a regular
// n-gon inscribed in a circle of radius r lies inside it by at most the
// sagitta r (1 - cos(pi / n)) (at each side's midpoint), so
//   n = ceil(pi / acos(1 - e)),  e the tolerated error relative to r.
// The default e = 1e-3 (0.1% of the radius: 0.1 mm on a 0.1 m wheel) gives
// 71 sides: a wheel rolling on them rises and falls by at most 0.1 mm once
// per side, 2 pi r / 71 = 8.8 mm of travel at r = 0.1 m, below anything a
// viewer or a controller sees. The inscribed volume is smaller than the
// cylinder's by the factor n sin(2 pi / n) / (2 pi), 0.13% at 71 sides; the
// mass properties are the hull's (the polygon's), exactly.
#pragma once

#include <memory>
#include <vector>

#include "service/physics/convex_hull.h"
#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

constexpr double kCylinderRelativeError = 1e-3;  // of the radius, the default bound
constexpr int kMaxCylinderSides = 512;            // a finer bound is clamped here

// Sides of the inscribed polygon whose radial error stays within
// `relative_error` of the radius (in (0, 1)); at least 3, at most
// kMaxCylinderSides.
int CylinderSides(double relative_error = kCylinderRelativeError);

// The 2n corner points of a cylinder of `radius` and `length` (m) along z,
// centred at the origin; the first at angle 0 on +x.
std::vector<Vec3> CylinderPoints(double radius, double length, int sides);

// The cylinder's hull with CylinderSides(relative_error) sides; its
// centroid is the origin. InvalidArgument naming radius or length when one
// is not a finite number > 0.
Status BuildCylinderHull(double radius, double length, std::shared_ptr<const ConvexHull>* hull,
                         double relative_error = kCylinderRelativeError);

}  // namespace contactsim
