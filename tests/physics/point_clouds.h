// Point clouds the hull tests share.
#pragma once

#include <cmath>
#include <vector>

#include "service/physics/math.h"

namespace contactsim {

// n points spread evenly over an ellipsoid with semi-axes r (a Fibonacci
// lattice), a stand-in for a mesh whose hull has every point as a vertex.
inline std::vector<Vec3> EllipsoidPoints(int n, const Vec3& r) {
  std::vector<Vec3> pts;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n;
    const double s = std::sqrt(1.0 - z * z);
    pts.emplace_back(r.x() * s * std::cos(golden * i), r.y() * s * std::sin(golden * i), r.z() * z);
  }
  return pts;
}

}  // namespace contactsim
