#include "service/model/urdf_reader.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <exception>
#include <mutex>

#include "service/model/description_check.h"
#include "service/model/description_meshes.h"
#include "service/model/urdf_structure.h"

namespace contactsim::model {
namespace {

// urdfdom reports through console_bridge's process-wide handler; while it
// parses, the errors go to a string for the Status instead of stderr.
class ConsoleCapture : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) messages += (messages.empty() ? "" : "; ") + text;
  }
  std::string messages;
};

std::mutex& ConsoleMutex() {
  static std::mutex m;
  return m;
}

urdf::ModelInterfaceSharedPtr ParseWithUrdfdom(const std::string& text, std::string* errors) {
  std::lock_guard<std::mutex> lock(ConsoleMutex());
  ConsoleCapture capture;
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    capture.messages += std::string(capture.messages.empty() ? "" : "; ") + e.what();
  }
  console_bridge::restorePreviousOutputHandler();
  *errors = capture.messages;
  return model;
}

Pose ToPose(const urdf::Pose& p) {
  Pose out;
  out.position = Vec3(p.position.x, p.position.y, p.position.z);
  out.orientation = Quat(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
  return out;
}

Vec3 ToVec(const urdf::Vector3& v) { return Vec3(v.x, v.y, v.z); }

Geometry ToGeometry(const urdf::Geometry& g) {
  Geometry out;
  switch (g.type) {
    case urdf::Geometry::BOX:
      out.type = GeometryType::kBox;
      out.box_size = ToVec(static_cast<const urdf::Box&>(g).dim);
      break;
    case urdf::Geometry::SPHERE:
      out.type = GeometryType::kSphere;
      out.radius = static_cast<const urdf::Sphere&>(g).radius;
      break;
    case urdf::Geometry::CYLINDER:
      out.type = GeometryType::kCylinder;
      out.radius = static_cast<const urdf::Cylinder&>(g).radius;
      out.length = static_cast<const urdf::Cylinder&>(g).length;
      break;
    case urdf::Geometry::MESH:
      out.type = GeometryType::kMesh;
      out.mesh_path = static_cast<const urdf::Mesh&>(g).filename;  // resolved by ResolveMeshes
      out.mesh_scale = ToVec(static_cast<const urdf::Mesh&>(g).scale);
      break;
  }
  return out;
}

std::optional<Inertial> ToInertial(const urdf::InertialSharedPtr& in) {
  if (!in || in->mass == 0.0) return std::nullopt;  // massless: no <inertial>, or mass 0 as PyBullet reads it
  Inertial out;
  out.mass = in->mass;
  out.origin = ToPose(in->origin);
  out.inertia << in->ixx, in->ixy, in->ixz, in->ixy, in->iyy, in->iyz, in->ixz, in->iyz, in->izz;
  return out;
}

Status ToLink(const urdf::Link& in, const SourceMap& where, Link* out) {
  out->name = in.name;
  out->inertial = ToInertial(in.inertial);
  for (const urdf::CollisionSharedPtr& c : in.collision_array) {
    if (!c->geometry) return Status::InvalidArgument(where.Link(in.name) + "a <collision> without a geometry");
    out->collisions.push_back(CollisionElement{c->name, ToPose(c->origin), ToGeometry(*c->geometry)});
  }
  for (const urdf::VisualSharedPtr& v : in.visual_array) {
    if (!v->geometry) return Status::InvalidArgument(where.Link(in.name) + "a <visual> without a geometry");
    VisualElement vis{v->name, ToPose(v->origin), ToGeometry(*v->geometry)};
    if (v->material) {
      const urdf::Color& c = v->material->color;
      vis.rgba = Eigen::Vector4d(c.r, c.g, c.b, c.a);
    }
    out->visuals.push_back(vis);
  }
  return Status::Ok();
}

JointType ToJointType(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return JointType::kRevolute;
    case urdf::Joint::CONTINUOUS: return JointType::kContinuous;
    case urdf::Joint::PRISMATIC: return JointType::kPrismatic;
    case urdf::Joint::FLOATING: return JointType::kFloating;
    case urdf::Joint::PLANAR: return JointType::kPlanar;
    default: return JointType::kFixed;  // urdf_structure.cpp refused every other word
  }
}

ModelJoint ToJoint(const urdf::Joint& in) {
  ModelJoint out;
  out.name = in.name;
  out.type = ToJointType(in.type);
  out.parent = in.parent_link_name;
  out.child = in.child_link_name;
  out.origin = ToPose(in.parent_to_joint_origin_transform);
  out.axis = HasAxis(out.type) ? ToVec(in.axis) : Vec3::UnitX();
  if (in.limits && out.type != JointType::kFixed && out.type != JointType::kFloating) {
    const bool bounded = out.type == JointType::kRevolute || out.type == JointType::kPrismatic;
    out.limits = JointLimits{bounded ? in.limits->lower : 0.0, bounded ? in.limits->upper : 0.0, in.limits->effort,
                             in.limits->velocity};
  }
  if (in.dynamics) {
    out.damping = in.dynamics->damping;
    out.friction = in.dynamics->friction;
  }
  if (in.mimic) out.mimic = ModelMimic{in.mimic->joint_name, in.mimic->multiplier, in.mimic->offset};
  return out;
}

// The link or joint an urdfdom message names ("... for Link [b]", "... for
// joint [j]"), as SourceMap words it with its line; the file alone if none.
std::string ElementNamedIn(const std::string& errors, const SourceMap& where) {
  for (const char* kind : {"Link [", "link [", "joint [", "Joint ["}) {
    const size_t at = errors.find(kind);
    if (at == std::string::npos) continue;
    const size_t start = at + std::string(kind).size();
    const size_t end = errors.find(']', start);
    if (end == std::string::npos) continue;
    const std::string name = errors.substr(start, end - start);
    if (where.link_lines.count(name) && (kind[0] == 'L' || kind[0] == 'l')) return where.Link(name);
    if (where.joint_lines.count(name) && (kind[0] == 'J' || kind[0] == 'j')) return where.Joint(name);
  }
  return where.File();
}

// urdfdom's model in the file's order (structure.link_order, joint_order).
Status Convert(const urdf::ModelInterface& in, const UrdfStructure& structure, const SourceMap& where,
               ModelDescription* out) {
  out->name = in.getName();
  for (const std::string& name : structure.link_order) {
    const auto it = in.links_.find(name);
    if (it == in.links_.end()) return Status::Internal(where.Link(name) + "urdfdom did not read this link");
    Link link;
    Status st = ToLink(*it->second, where, &link);
    if (!st.ok()) return st;
    out->links.push_back(std::move(link));
  }
  for (const std::string& name : structure.joint_order) {
    const auto it = in.joints_.find(name);
    if (it == in.joints_.end()) return Status::Internal(where.Joint(name) + "urdfdom did not read this joint");
    out->joints.push_back(ToJoint(*it->second));
  }
  out->root_link = structure.root_link;
  return Status::Ok();
}

}  // namespace

Status ReadUrdf(const std::string& text, const std::string& source_path, const ModelPaths& paths,
                const ReadLimits& limits, ModelDescription* model) {
  SourceMap where;
  if (Status s = CheckFileSize(text, source_path, limits, &where); !s.ok()) return s;
  UrdfStructure structure;
  Status st = ReadUrdfStructure(text, limits, &where, &structure);
  if (!st.ok()) return st;
  std::string errors;
  const urdf::ModelInterfaceSharedPtr parsed = ParseWithUrdfdom(text, &errors);
  // urdfdom logs some refusals (a number it cannot parse, an unknown
  // geometry) and goes on without the element: any error refuses the file
  if (!parsed || !errors.empty()) {
    return Status::InvalidArgument(ElementNamedIn(errors, where) + "urdfdom refuses the file: " + errors);
  }
  ModelDescription out;
  out.source = where.file;
  st = Convert(*parsed, structure, where, &out);
  if (st.ok()) st = CheckValues(where, &out);
  if (st.ok()) st = ResolveMeshes(DirectoryOf(where.file), paths, limits, where, &out);
  if (!st.ok()) return st;
  *model = std::move(out);
  return Status::Ok();
}

}  // namespace contactsim::model
