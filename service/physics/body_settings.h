// The settings of a new body, as they arrive from a command or a scene file,
// and the one gate that turns them into a RigidBody (as Jolt's
// BodyCreationSettings): invalid settings never reach the world.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "service/physics/rigid_body.h"
#include "service/physics/status.h"

namespace contactsim {

struct BodySettings {
  std::string name;
  ShapeType shape = ShapeType::kSphere;
  double radius = 0.0;                    // m, sphere and capsule
  Vec3 half_extents = Vec3::Zero();       // m, box
  double half_length = 0.0;               // m, capsule
  Vec3 plane_normal = Vec3::UnitZ();      // plane, world (normalised here)
  double plane_offset = 0.0;              // m, plane
  std::vector<Vec3> points;               // m, convex, in the body's frame
  std::optional<double> mass;             // kg
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
// and the message names the field and the value. For a convex shape the
// hull's centre of mass becomes the body origin, so `position` (the origin
// of the points' frame) is moved to it.
Status CreateBody(const BodySettings& settings, const Material& default_material, RigidBody* body);

// Validates restitution and friction for SET_MATERIAL-like changes.
Status CheckMaterial(std::optional<double> restitution, std::optional<double> friction);

}  // namespace contactsim
