// A robot model as its file describes it (URDF or SDF), before it becomes
// bodies and joints: links with their inertial, collision and visual
// elements, and the joints between them, every pose relative to the frame
// the format names. The readers (urdf_reader.h, sdf_reader.h) fill it from
// a file; model_builder.h turns it into world bodies and joints. Keeping the
// two apart lets the readers be tested against the file's own numbers and
// the builder against hand-made descriptions. docs/models.md says what is
// read and what is not.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "service/physics/math.h"

namespace contactsim::model {

// A frame relative to a parent frame: p_parent = position + orientation * p_child.
struct Pose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

enum class GeometryType { kBox, kSphere, kCylinder, kCapsule, kMesh };

// One collision or visual geometry in its own frame. A cylinder and a
// capsule have their axis along the frame's z (URDF and SDF both do).
struct Geometry {
  GeometryType type = GeometryType::kBox;
  Vec3 box_size = Vec3::Zero();       // m, full edge lengths (URDF <box size>)
  double radius = 0.0;                // m, sphere, cylinder, capsule
  double length = 0.0;                // m, cylinder and capsule: length of the axis part
  std::string mesh_path;              // mesh: the resolved file path (absolute)
  Vec3 mesh_scale = Vec3::Ones();     // mesh: per-axis scale from the file
  std::vector<Vec3> mesh_vertices;    // mesh: every vertex, scaled, in the geometry frame
};

struct CollisionElement {
  std::string name;                   // may be empty
  Pose origin;                        // geometry frame in the link frame
  Geometry geometry;
};

struct VisualElement {
  std::string name;
  Pose origin;                        // geometry frame in the link frame
  Geometry geometry;                  // a mesh keeps mesh_path for the viewer
  Eigen::Vector4d rgba{0.7, 0.7, 0.7, 1.0};
};

struct Inertial {
  double mass = 0.0;                  // kg
  Pose origin;                        // centre-of-mass frame in the link frame
  Mat3 inertia = Mat3::Zero();        // kg m^2, about the centre of mass, in origin's axes
};

struct Link {
  std::string name;
  std::optional<Inertial> inertial;   // none: a massless frame (merged or refused by the builder)
  std::vector<CollisionElement> collisions;
  std::vector<VisualElement> visuals;
};

enum class JointType { kRevolute, kContinuous, kPrismatic, kFixed, kFloating, kPlanar };

// Each joint type's name as URDF spells it, for replies and messages.
inline const char* JointTypeName(JointType type) {
  switch (type) {
    case JointType::kRevolute: return "revolute";
    case JointType::kContinuous: return "continuous";
    case JointType::kPrismatic: return "prismatic";
    case JointType::kFixed: return "fixed";
    case JointType::kFloating: return "floating";
    case JointType::kPlanar: return "planar";
  }
  return "unknown";
}

struct JointLimits {
  double lower = 0.0, upper = 0.0;    // rad or m; only for revolute and prismatic
  double effort = 0.0;                // N m or N; 0: none given
  double velocity = 0.0;              // rad/s or m/s; 0: none given
};

// URDF's <mimic joint multiplier offset>: this joint's coordinate is
// multiplier * q_joint + offset.
struct ModelMimic {
  std::string joint;                  // the master joint's name
  double multiplier = 1.0;
  double offset = 0.0;                // rad or m
};

struct ModelJoint {
  std::string name;
  JointType type = JointType::kFixed;
  std::string parent, child;          // link names
  Pose origin;                        // child link frame in the parent link frame at q = 0
  Vec3 axis = Vec3::UnitX();          // unit, in the child link frame (URDF's default is x)
  std::optional<JointLimits> limits;
  double damping = 0.0;               // N m s/rad or N s/m (<dynamics>)
  double friction = 0.0;              // N m or N, Coulomb (<dynamics>)
  std::optional<ModelMimic> mimic;    // URDF <mimic>; SDF gives none
};

struct ModelDescription {
  std::string name;                   // the file's robot/model name
  std::string source;                 // file path, or "<inline>"
  std::vector<Link> links;            // in the file's order
  std::vector<ModelJoint> joints;     // in the file's order
  bool self_collide = false;          // SDF <self_collide>; URDF has none (false)
  // The link that no joint names as a child; empty until the reader checks
  // the tree.
  std::string root_link;
};

}  // namespace contactsim::model
