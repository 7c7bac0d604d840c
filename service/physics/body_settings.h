// The settings of a new body, as they arrive from a command or a scene file,
// and the one gate that turns them into a RigidBody (as Jolt's
// BodyCreationSettings): invalid settings never reach the world.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "service/physics/rigid_body.h"
#include "service/physics/status.h"

namespace contactsim {

class HullMemo;  // hull_memo.h

// One shape of a compound body, posed in the frame that
// BodySettings::position and orientation place in the world (a robot
// link's frame): a sphere, box, capsule or convex hull, with the same
// fields as a single shape.
struct ShapePart {
  ShapeType type = ShapeType::kSphere;
  double radius = 0.0;                    // m, sphere and capsule
  Vec3 half_extents = Vec3::Zero();       // m, box
  double half_length = 0.0;               // m, capsule: cap centres at (0, 0, +-half_length)
  std::vector<Vec3> points;               // m, convex, in the part's frame
  Vec3 position = Vec3::Zero();           // m, the part's frame in the settings' frame
  Quat orientation = Quat::Identity();    // part to settings' frame; normalised here
};

// Most parts one body takes: a robot link has a handful of collision
// elements; more would make every pair of it cost parts^2 child pairs.
constexpr int kMaxShapeParts = 64;

struct BodySettings {
  std::string name;
  ShapeType shape = ShapeType::kSphere;
  double radius = 0.0;                    // m, sphere and capsule
  Vec3 half_extents = Vec3::Zero();       // m, box
  double half_length = 0.0;               // m, capsule
  Vec3 plane_normal = Vec3::UnitZ();      // plane, world (normalised here)
  double plane_offset = 0.0;              // m, plane
  std::vector<Vec3> points;               // m, convex, in the body's frame
  std::vector<ShapePart> parts;           // compound: the shapes, 1 to kMaxShapeParts
  // mesh and heightfield: the surface, built and checked by the collision
  // layer (BuildTriangleMesh, BuildHeightField); always static
  std::shared_ptr<const TriangleMesh> mesh;
  std::shared_ptr<const HeightField> heightfield;
  std::optional<double> mass;             // kg
  // Explicit mass properties, for any shape (a robot link's inertial):
  // the centre of mass (m, in the settings' frame) and the inertia about
  // it (kg m^2, in the settings' axes; needs `mass`). Without them they
  // come from the shape at uniform density.
  std::optional<Vec3> center_of_mass;
  std::optional<Mat3> inertia;
  std::optional<double> density;          // kg/m^3; default kDefaultDensity
  bool fixed = false;                     // static body
  bool kinematic = false;                 // infinite mass, moves with its velocity
  Vec3 position = Vec3::Zero();           // m, world
  Eigen::Vector4d orientation{1, 0, 0, 0};// (w, x, y, z); normalised here
  Vec3 linear_velocity = Vec3::Zero();    // m/s, world
  Vec3 angular_velocity = Vec3::Zero();   // rad/s, world
  std::optional<double> restitution;      // [0, 1]; default from the world's material
  std::optional<double> friction;         // >= 0
  uint32_t collision_category = 1;        // collision_filter.h
  uint32_t collision_mask = 0xFFFFFFFF;
  int32_t collision_group = 0;
};

constexpr double kDefaultDensity = 1000.0;  // kg/m^3, water

// Validates every field and builds the body; on error `body` is untouched
// and the message names the field and the value. The centre of mass
// becomes the body origin (a hull's, a compound's, or the explicit one),
// so `position` (the origin of the settings' frame) is moved to it and kept
// as RigidBody::frame_origin; the body axes are the settings' axes. A
// single shape whose centre is not the centre of mass becomes a compound
// of one child, exactly (docs/physics.md, "Compound bodies and mass
// properties"). Hulls come from `memo` when given (hull_memo.h: a model's
// links that share a mesh or a cylinder's size build its hull once).
Status CreateBody(const BodySettings& settings, const Material& default_material, RigidBody* body,
                  HullMemo* memo = nullptr);

// Validates restitution and friction for SET_MATERIAL-like changes.
Status CheckMaterial(std::optional<double> restitution, std::optional<double> friction);

}  // namespace contactsim
