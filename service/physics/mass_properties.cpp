#include "service/physics/mass_properties.h"

#include <cmath>

#include "service/physics/convex_hull.h"

namespace contactsim {
namespace {

// Solid capsule about its centre, axis z: a cylinder of length 2h plus two
// hemispheres whose centres of mass sit 3r/8 beyond the cylinder ends
// (parallel-axis theorem for the transverse moment).
Mat3 CapsuleInertia(double r, double h, double density) {
  const double m_cyl = density * kPi * r * r * 2.0 * h;
  const double m_hemi = density * 2.0 / 3.0 * kPi * r * r * r;  // one hemisphere
  const double izz = m_cyl * r * r / 2.0 + 2.0 * m_hemi * 2.0 / 5.0 * r * r;
  // transverse: cylinder m (3 r^2 + L^2) / 12 with L = 2h; hemisphere about its
  // own centre of mass 83/320 m r^2, shifted to the capsule centre by h + 3r/8
  const double d = h + 3.0 * r / 8.0;
  const double ixx = m_cyl * (3.0 * r * r + 4.0 * h * h) / 12.0 +
                     2.0 * (83.0 / 320.0 * m_hemi * r * r + m_hemi * d * d);
  return Eigen::Vector3d(ixx, ixx, izz).asDiagonal();
}

}  // namespace

double ShapeVolume(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kSphere: return 4.0 / 3.0 * kPi * shape.radius * shape.radius * shape.radius;
    case ShapeType::kBox: return 8.0 * shape.half_extents.prod();
    case ShapeType::kCapsule:
      return kPi * shape.radius * shape.radius * (2.0 * shape.half_length + 4.0 / 3.0 * shape.radius);
    case ShapeType::kConvex: return shape.hull ? ConvexHullVolume(*shape.hull) : 0.0;
    case ShapeType::kPlane:
    case ShapeType::kCount: break;
  }
  return 0.0;
}

MassProperties ComputeMassProperties(const Shape& shape, double density) {
  MassProperties mp;
  switch (shape.type) {
    case ShapeType::kSphere: {
      mp.mass = density * ShapeVolume(shape);
      mp.inertia = Mat3::Identity() * (0.4 * mp.mass * shape.radius * shape.radius);
      break;
    }
    case ShapeType::kBox: {
      // I_xx = m/3 (b^2 + c^2) for half extents (a, b, c)
      mp.mass = density * ShapeVolume(shape);
      const Vec3 e2 = shape.half_extents.cwiseProduct(shape.half_extents);
      mp.inertia = (mp.mass / 3.0 * Vec3(e2.y() + e2.z(), e2.x() + e2.z(), e2.x() + e2.y())).asDiagonal();
      break;
    }
    case ShapeType::kCapsule: {
      mp.mass = density * ShapeVolume(shape);
      mp.inertia = CapsuleInertia(shape.radius, shape.half_length, density);
      break;
    }
    case ShapeType::kConvex: {
      if (shape.hull) mp = ConvexHullMassProperties(*shape.hull, density);
      break;
    }
    case ShapeType::kPlane:
    case ShapeType::kCount: break;
  }
  return mp;
}

}  // namespace contactsim
