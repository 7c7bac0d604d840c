// A tilted static plane for the slope scenes of the method scenario suites.
#pragma once

#include <Eigen/Geometry>

#include "tests/contact/test_bodies.h"

namespace contactsim {
namespace testing {

// A static plane through the origin tilted by `angle` about y; `downhill`
// is the unit vector down the slope in the plane (tilting +x about y lowers
// it: x' = (cos a, 0, -sin a)). Returns the tilt.
inline Quat AddSlope(World& world, double angle, double mu, Vec3* downhill) {
  const Quat tilt(Eigen::AngleAxisd(angle, Vec3::UnitY()));
  BodySettings plane;
  plane.shape = ShapeType::kPlane;
  plane.plane_normal = tilt * Vec3::UnitZ();
  plane.restitution = 0.0;
  plane.friction = mu;
  AddValidBody(world, plane);
  *downhill = tilt * Vec3::UnitX();
  return tilt;
}

}  // namespace testing
}  // namespace contactsim
