#include "service/model/sdf_elements.h"

#include <sdf/Box.hh>
#include <sdf/Capsule.hh>
#include <sdf/Collision.hh>
#include <sdf/Cylinder.hh>
#include <sdf/Geometry.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Material.hh>
#include <sdf/Mesh.hh>
#include <sdf/Sphere.hh>
#include <sdf/Visual.hh>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "service/model/model_kinematics.h"

namespace contactsim::model {
namespace {

// SDF's default joint limits (+-1e16) mean "none".
constexpr double kSdfUnbounded = 1e16;

// A mesh name relative to the file it was written in (an <include>d model's
// own file), as SDF resolves it; URIs are left to ResolveMeshes.
std::string MeshName(const sdf::Mesh& mesh) {
  const std::string uri = mesh.Uri();
  const std::filesystem::path from = mesh.FilePath();
  std::error_code ec;
  if (uri.find("://") != std::string::npos || std::filesystem::path(uri).is_absolute() ||
      !std::filesystem::is_regular_file(from, ec)) {
    return uri;  // the text given to the reader has no file of its own
  }
  return (from.parent_path() / uri).string();
}

const char* SdfJointTypeName(sdf::JointType t) {
  switch (t) {
    case sdf::JointType::BALL: return "ball";
    case sdf::JointType::GEARBOX: return "gearbox";
    case sdf::JointType::REVOLUTE2: return "revolute2";
    case sdf::JointType::SCREW: return "screw";
    case sdf::JointType::UNIVERSAL: return "universal";
    default: return "invalid";
  }
}

}  // namespace

Status SdfGeometry(const sdf::Geometry& in, const std::string& where, Geometry* out) {
  switch (in.Type()) {
    case sdf::GeometryType::BOX: {
      const auto& s = in.BoxShape()->Size();
      out->type = GeometryType::kBox;
      out->box_size = Vec3(s.X(), s.Y(), s.Z());
      return Status::Ok();
    }
    case sdf::GeometryType::SPHERE:
      out->type = GeometryType::kSphere;
      out->radius = in.SphereShape()->Radius();
      return Status::Ok();
    case sdf::GeometryType::CYLINDER:
      out->type = GeometryType::kCylinder;
      out->radius = in.CylinderShape()->Radius();
      out->length = in.CylinderShape()->Length();
      return Status::Ok();
    case sdf::GeometryType::CAPSULE:
      out->type = GeometryType::kCapsule;
      out->radius = in.CapsuleShape()->Radius();
      out->length = in.CapsuleShape()->Length();
      return Status::Ok();
    case sdf::GeometryType::MESH: {
      const sdf::Mesh& m = *in.MeshShape();
      if (!m.Submesh().empty()) return Status::InvalidArgument(where + "a <submesh> is not read");
      out->type = GeometryType::kMesh;
      out->mesh_path = MeshName(m);
      out->mesh_scale = Vec3(m.Scale().X(), m.Scale().Y(), m.Scale().Z());
      return Status::Ok();
    }
    default:
      return Status::InvalidArgument(where + "geometry of this type (plane, ellipsoid, heightmap, polyline or "
                                             "empty) is not read: box, sphere, cylinder, capsule and mesh are");
  }
}

// the link frame in the description frame, then each element in the link frame
Status SdfLinkElements(const FlatSdfLink& flat, const Pose& frame, const SourceMap& where, Link* out) {
  const Pose link_in_frame = Compose(InversePose(frame), flat.pose);
  const std::string w = where.Link(flat.name);
  out->name = flat.name;
  const ignition::math::Inertiald& in = flat.link->Inertial();
  if (in.MassMatrix().Mass() != 0.0) {
    Inertial inertial;
    inertial.mass = in.MassMatrix().Mass();
    inertial.origin = Compose(link_in_frame, FromIgnition(in.Pose()));
    const ignition::math::Matrix3d moi = in.MassMatrix().Moi();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) inertial.inertia(r, c) = moi(r, c);
    }
    out->inertial = inertial;
  }
  for (uint64_t i = 0; i < flat.link->CollisionCount(); ++i) {
    const sdf::Collision& c = *flat.link->CollisionByIndex(i);
    ignition::math::Pose3d p;  // in the link frame, a collision's default
    const sdf::Errors errors = c.SemanticPose().Resolve(p);
    if (!errors.empty()) return Status::InvalidArgument(w + "collision '" + c.Name() + "': " + FirstError(errors));
    CollisionElement e{c.Name(), Compose(link_in_frame, FromIgnition(p)), {}};
    Status st = SdfGeometry(*c.Geom(), w + "collision '" + c.Name() + "': ", &e.geometry);
    if (!st.ok()) return st;
    out->collisions.push_back(e);
  }
  for (uint64_t i = 0; i < flat.link->VisualCount(); ++i) {
    const sdf::Visual& v = *flat.link->VisualByIndex(i);
    ignition::math::Pose3d p;
    const sdf::Errors errors = v.SemanticPose().Resolve(p);
    if (!errors.empty()) return Status::InvalidArgument(w + "visual '" + v.Name() + "': " + FirstError(errors));
    VisualElement e{v.Name(), Compose(link_in_frame, FromIgnition(p)), {}};
    Status st = SdfGeometry(*v.Geom(), w + "visual '" + v.Name() + "': ", &e.geometry);
    if (!st.ok()) return st;
    if (v.Material() != nullptr) {
      const auto& d = v.Material()->Diffuse();
      e.rgba = Eigen::Vector4d(d.R(), d.G(), d.B(), d.A());
    }
    out->visuals.push_back(e);
  }
  return Status::Ok();
}

// Type, axis, limits and dynamics of a revolute, continuous, prismatic or
// fixed joint.
Status SdfJointMotion(const sdf::Joint& in, const std::string& where, ModelJoint* out) {
  switch (in.Type()) {
    case sdf::JointType::REVOLUTE: out->type = JointType::kRevolute; break;
    case sdf::JointType::CONTINUOUS: out->type = JointType::kContinuous; break;
    case sdf::JointType::PRISMATIC: out->type = JointType::kPrismatic; break;
    case sdf::JointType::FIXED: out->type = JointType::kFixed; return Status::Ok();
    default:
      return Status::InvalidArgument(where + "joint type '" + SdfJointTypeName(in.Type()) +
                                     "' is not supported (revolute, continuous, prismatic and fixed are)");
  }
  const sdf::JointAxis* axis = in.Axis(0);
  if (axis == nullptr) return Status::InvalidArgument(where + "no <axis>");
  ignition::math::Vector3d xyz;  // in the joint frame, the default
  const sdf::Errors errors = axis->ResolveXyz(xyz);
  if (!errors.empty()) return Status::InvalidArgument(where + "axis: " + FirstError(errors));
  out->axis = Vec3(xyz.X(), xyz.Y(), xyz.Z());
  out->damping = axis->Damping();
  out->friction = axis->Friction();
  const bool bounded = axis->Lower() > -kSdfUnbounded || axis->Upper() < kSdfUnbounded;
  if (out->type == JointType::kRevolute && !bounded) out->type = JointType::kContinuous;
  // SDF writes "no limit" as -1 or infinity; the description as 0
  auto given = [](double v) { return std::isfinite(v) && v > 0.0 ? v : 0.0; };
  const double effort = given(axis->Effort()), velocity = given(axis->MaxVelocity());
  if (out->type == JointType::kContinuous && (effort > 0.0 || velocity > 0.0)) {
    out->limits = JointLimits{0.0, 0.0, effort, velocity};
  } else if (out->type != JointType::kContinuous && bounded) {
    out->limits = JointLimits{axis->Lower(), axis->Upper(), effort, velocity};
  }
  return Status::Ok();
}

}  // namespace contactsim::model
