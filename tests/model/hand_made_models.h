// Hand-made robot model descriptions for the builder's and the server's
// tests: links whose one collision sphere sits at the centre of mass with
// the solid sphere's inertia, and revolute joints with limits.
#pragma once

#include <string>

#include "service/model/model_description.h"

namespace contactsim::model::testing {

inline constexpr double kArmPi = 3.14159265358979323846;

// A link whose one collision sphere sits at its centre of mass with the
// solid sphere's inertia, so the engine's shape-derived mass properties are
// the file's exactly.
inline Link SphereLink(const std::string& name, double mass, double radius, const Vec3& com) {
  Link l;
  l.name = name;
  Inertial in;
  in.mass = mass;
  in.origin.position = com;
  in.inertia = 0.4 * mass * radius * radius * Mat3::Identity();
  l.inertial = in;
  CollisionElement c;
  c.origin.position = com;
  c.geometry.type = GeometryType::kSphere;
  c.geometry.radius = radius;
  l.collisions.push_back(c);
  return l;
}

inline ModelJoint Revolute(const std::string& name, const std::string& parent, const std::string& child, const Vec3& xyz,
                    const Vec3& axis) {
  ModelJoint j;
  j.name = name;
  j.type = JointType::kRevolute;
  j.parent = parent;
  j.child = child;
  j.origin.position = xyz;
  j.axis = axis;
  j.limits = JointLimits{-1.0, 2.0, 10.0, 3.0};
  return j;
}

// A three-link arm: base, upper arm 0.5 m above it, forearm 0.4 m along
// the upper arm's x; the second joint's frame is turned 90 degrees about z.
inline ModelDescription Arm() {
  ModelDescription d;
  d.name = "arm";
  d.source = "<inline>";
  d.links = {SphereLink("base", 2.0, 0.1, Vec3::Zero()), SphereLink("upper", 1.0, 0.05, Vec3(0.1, 0, 0)),
             SphereLink("fore", 0.5, 0.04, Vec3(0.2, 0, 0))};
  d.joints = {Revolute("shoulder", "base", "upper", Vec3(0, 0, 0.5), Vec3::UnitY()),
              Revolute("elbow", "upper", "fore", Vec3(0.4, 0, 0), Vec3::UnitZ())};
  d.joints[1].origin.orientation = Quat(Eigen::AngleAxisd(kArmPi / 2, Vec3::UnitZ()));
  return d;
}

}  // namespace contactsim::model::testing
