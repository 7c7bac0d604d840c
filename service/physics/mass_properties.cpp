#include "service/physics/mass_properties.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "service/physics/convex_hull.h"
#include "service/physics/validation.h"

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

// Children summed: m = sum m_i, c = sum m_i c_i / m,
// I_c = sum (R_i I_i R_i^T + m_i (|d_i|^2 E - d_i d_i^T)), d_i = c_i - c.
MassProperties CompoundMassProperties(const CompoundShape& compound, double density) {
  MassProperties mp;
  Vec3 moment = Vec3::Zero();
  for (const ShapeChild& child : compound.children) {
    const MassProperties part = ComputeMassProperties(child.shape, density);
    mp.mass += part.mass;
    moment += part.mass * (child.position + child.orientation * part.center);
  }
  if (mp.mass <= 0.0) return mp;
  mp.center = moment / mp.mass;
  for (const ShapeChild& child : compound.children) {
    const MassProperties part = ComputeMassProperties(child.shape, density);
    const Mat3 R = child.orientation.toRotationMatrix();
    const Vec3 d = child.position + child.orientation * part.center - mp.center;
    mp.inertia += ShiftInertia(R * part.inertia * R.transpose(), part.mass, d);
  }
  return mp;
}

}  // namespace

Mat3 ShiftInertia(const Mat3& inertia_c, double mass, const Vec3& d) {
  return inertia_c + mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
}

Mat3 InertiaAboutOrigin(const MassProperties& mp) {
  // a centred shape keeps its tensor bit for bit
  if (mp.center.isZero(0.0)) return mp.inertia;
  return ShiftInertia(mp.inertia, mp.mass, mp.center);
}

Status CheckInertiaTensor(const std::string& field, const Mat3& I) {
  auto text = [&I]() {
    return "[[" + FormatValue(Vec3(I.row(0).transpose())) + ", " + FormatValue(Vec3(I.row(1).transpose())) + ", " +
           FormatValue(Vec3(I.row(2).transpose())) + "]]";
  };
  if (!I.allFinite()) return Status::InvalidArgument(field + " must be finite, got " + text());
  const double scale = I.cwiseAbs().maxCoeff();
  if ((I - I.transpose()).cwiseAbs().maxCoeff() > 1e-9 * scale) {
    return Status::InvalidArgument(field + " must be symmetric, got " + text());
  }
  const Vec3 moments = Eigen::SelfAdjointEigenSolver<Mat3>(0.5 * (I + I.transpose()), Eigen::EigenvaluesOnly)
                           .eigenvalues();  // ascending
  if (!(moments[0] > 0.0)) {
    return Status::InvalidArgument(field + " must be positive definite, got principal moments " +
                                   FormatValue(moments) + " from " + text());
  }
  if (moments[0] + moments[1] < moments[2] * (1.0 - 1e-9)) {
    return Status::InvalidArgument(field + " breaks the triangle inequality of principal moments (I1 + I2 >= I3), "
                                   "got principal moments " + FormatValue(moments) + " from " + text());
  }
  return Status::Ok();
}

double ShapeVolume(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kSphere: return 4.0 / 3.0 * kPi * shape.radius * shape.radius * shape.radius;
    case ShapeType::kBox: return 8.0 * shape.half_extents.prod();
    case ShapeType::kCapsule:
      return kPi * shape.radius * shape.radius * (2.0 * shape.half_length + 4.0 / 3.0 * shape.radius);
    case ShapeType::kConvex: return shape.hull ? ConvexHullVolume(*shape.hull) : 0.0;
    case ShapeType::kCompound: {
      double volume = 0.0;
      if (shape.compound) {
        for (const ShapeChild& child : shape.compound->children) volume += ShapeVolume(child.shape);
      }
      return volume;
    }
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
    case ShapeType::kCompound: {
      if (shape.compound) mp = CompoundMassProperties(*shape.compound, density);
      break;
    }
    case ShapeType::kPlane:
    case ShapeType::kCount: break;
  }
  return mp;
}

}  // namespace contactsim
