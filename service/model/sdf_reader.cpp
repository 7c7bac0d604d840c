#include "service/model/sdf_reader.h"

#include <sdf/Console.hh>
#include <sdf/Geometry.hh>
#include <sdf/Box.hh>
#include <sdf/Capsule.hh>
#include <sdf/Collision.hh>
#include <sdf/Cylinder.hh>
#include <sdf/JointAxis.hh>
#include <sdf/Material.hh>
#include <sdf/Mesh.hh>
#include <sdf/ParserConfig.hh>
#include <sdf/Root.hh>
#include <sdf/Sphere.hh>
#include <sdf/Visual.hh>
#include <sdf/World.hh>

#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>

#include "service/model/description_check.h"
#include "service/model/description_meshes.h"
#include "service/model/model_kinematics.h"
#include "service/model/sdf_flatten.h"
#include "service/model/source_map.h"

namespace contactsim::model {
namespace {

// SDF's default joint limits (+-1e16) mean "none".
constexpr double kSdfUnbounded = 1e16;

Pose Inverse(const Pose& p) {
  Pose out;
  out.orientation = p.orientation.conjugate();
  out.position = -(out.orientation * p.position);
  return out;
}

// Parses the text; <include> URIs resolve with model_paths.h.
Status LoadRoot(const std::string& text, const std::string& base_dir, const ModelPaths& paths, const SourceMap& where,
                sdf::Root* root) {
  static std::once_flag quiet;
  std::call_once(quiet, [] { sdf::Console::Instance()->SetQuiet(true); });  // errors come back as values
  sdf::ParserConfig config;
  config.SetFindCallback([&](const std::string& uri) {
    std::string found;
    return ResolveModelUri(uri, base_dir, paths, &found).ok() ? found : std::string();
  });
  const sdf::Errors errors = root->LoadSdfString(text, config);
  if (!errors.empty()) return Status::InvalidArgument(where.File() + "libsdformat refuses the file: " + FirstError(errors));
  return Status::Ok();
}

Status PickModel(const sdf::Root& root, const SourceMap& where, const sdf::Model** model) {
  if (root.Model() != nullptr) {
    *model = root.Model();
    return Status::Ok();
  }
  if (root.WorldCount() == 0 || root.WorldByIndex(0)->ModelCount() == 0) {
    return Status::InvalidArgument(where.File() + "no <model>, at the top or in a <world>");
  }
  const sdf::World& world = *root.WorldByIndex(0);
  if (root.WorldCount() > 1 || world.ModelCount() > 1) {
    std::string names;
    for (uint64_t i = 0; i < world.ModelCount(); ++i) names += (i ? ", '" : "'") + world.ModelByIndex(i)->Name() + "'";
    return Status::InvalidArgument(where.File() + "the world holds " + std::to_string(world.ModelCount()) +
                                   " models (" + names + "); a file must hold one model");
  }
  *model = world.ModelByIndex(0);
  return Status::Ok();
}

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

Status ToGeometry(const sdf::Geometry& in, const std::string& where, Geometry* out) {
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

// The link's elements in the description frame F_top (top model frame).
Status ToLink(const FlatSdfLink& flat, const Pose& frame, const SourceMap& where, Link* out) {
  const Pose link_in_frame = Compose(Inverse(frame), flat.pose);
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
    Status st = ToGeometry(*c.Geom(), w + "collision '" + c.Name() + "': ", &e.geometry);
    if (!st.ok()) return st;
    out->collisions.push_back(e);
  }
  for (uint64_t i = 0; i < flat.link->VisualCount(); ++i) {
    const sdf::Visual& v = *flat.link->VisualByIndex(i);
    ignition::math::Pose3d p;
    const sdf::Errors errors = v.SemanticPose().Resolve(p);
    if (!errors.empty()) return Status::InvalidArgument(w + "visual '" + v.Name() + "': " + FirstError(errors));
    VisualElement e{v.Name(), Compose(link_in_frame, FromIgnition(p)), {}};
    Status st = ToGeometry(*v.Geom(), w + "visual '" + v.Name() + "': ", &e.geometry);
    if (!st.ok()) return st;
    if (v.Material() != nullptr) {
      const auto& d = v.Material()->Diffuse();
      e.rgba = Eigen::Vector4d(d.R(), d.G(), d.B(), d.A());
    }
    out->visuals.push_back(e);
  }
  return Status::Ok();
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

// Type, axis, limits and dynamics of a revolute, continuous, prismatic or
// fixed joint.
Status ToJointMotion(const sdf::Joint& in, const std::string& where, ModelJoint* out) {
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

// The flat lists as a description with names only, for the tree check.
ModelDescription Skeleton(const FlatSdfModel& flat) {
  ModelDescription d;
  for (const FlatSdfLink& l : flat.links) d.links.push_back(Link{l.name, std::nullopt, {}, {}});
  for (const FlatSdfJoint& j : flat.joints) {
    ModelJoint mj;
    mj.name = j.name;
    mj.parent = j.parent;
    mj.child = j.child;
    d.joints.push_back(mj);
  }
  return d;
}

// Fills links and joints; a link's frame is its parent joint's frame, the
// root's its own (sdf_reader.h, "Frames").
Status Convert(const FlatSdfModel& flat, const SourceMap& where, ModelDescription* out) {
  std::map<std::string, Pose> frame;
  for (const FlatSdfLink& l : flat.links) frame[l.name] = l.pose;
  for (const FlatSdfJoint& j : flat.joints) frame[j.child] = j.pose;
  for (size_t i = 0; i < flat.links.size(); ++i) {
    Status st = ToLink(flat.links[i], frame.at(flat.links[i].name), where, &out->links[i]);
    if (!st.ok()) return st;
  }
  for (size_t i = 0; i < flat.joints.size(); ++i) {
    const FlatSdfJoint& j = flat.joints[i];
    ModelJoint& mj = out->joints[i];
    mj.origin = Compose(Inverse(frame.at(j.parent)), frame.at(j.child));
    Status st = ToJointMotion(*j.joint, where.Joint(j.name), &mj);
    if (!st.ok()) return st;
  }
  return Status::Ok();
}

Status CheckWorldJoints(const FlatSdfModel& flat, const SourceMap& where) {
  for (const FlatSdfJoint& j : flat.joints) {
    if (j.parent == "world" || j.child == "world") {
      return Status::InvalidArgument(where.Joint(j.name) +
                                     "a joint to the world is not read; load the model with a fixed base instead");
    }
  }
  return Status::Ok();
}

}  // namespace

Status ReadSdf(const std::string& text, const std::string& source_path, const ModelPaths& paths,
               const ReadLimits& limits, ModelDescription* model) {
  SourceMap where;
  where.file = source_path.empty() ? "<inline>" : source_path;
  if (text.size() > limits.max_file_bytes) {
    return Status::ResourceExhausted(where.File() + std::to_string(text.size()) + " bytes, over the limit of " +
                                     std::to_string(limits.max_file_bytes) + " (max_file_bytes)");
  }
  sdf::Root root;
  const sdf::Model* top = nullptr;
  Status st = LoadRoot(text, DirectoryOf(where.file), paths, where, &root);
  if (st.ok()) st = PickModel(root, where, &top);
  FlatSdfModel flat;
  if (st.ok()) {
    st = FlattenSdfModel(*top, "", Pose{}, &flat);
    if (!st.ok()) st = st.Prefixed(where.File());
  }
  if (!st.ok()) return st;
  for (const FlatSdfLink& l : flat.links) where.link_lines[l.name] = l.line;
  for (const FlatSdfJoint& j : flat.joints) where.joint_lines[j.name] = j.line;
  ModelDescription out = Skeleton(flat);
  out.name = top->Name();
  out.source = where.file;
  out.self_collide = top->SelfCollide();
  st = CheckCounts(flat.links.size(), flat.joints.size(), limits, where);
  if (st.ok()) st = CheckWorldJoints(flat, where);
  if (st.ok()) st = CheckTree(where, &out);
  if (st.ok()) st = Convert(flat, where, &out);
  if (st.ok()) st = CheckValues(where, &out);
  if (st.ok()) st = ResolveMeshes(DirectoryOf(where.file), paths, limits, where, &out);
  if (!st.ok()) return st;
  *model = std::move(out);
  return Status::Ok();
}

}  // namespace contactsim::model
