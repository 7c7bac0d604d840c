// The world's record of the robot models it holds: which bodies and joints
// came from which model file, under which names. A model is added and
// removed as a whole; the record lets a client that joins later map the
// file's link and joint names to ids, and lets the server report each
// link's frame, which is not its body's frame when the link's centre of
// mass is off its origin or the link was merged into its parent.
//
// The record is bookkeeping, not state the physics reads: it travels with
// the world (snapshots, the server's undo copy, REWIND) but is not part of
// the state hash.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "service/physics/joint.h"
#include "service/physics/math.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

using ModelId = int64_t;

// One visual element of a link as the file gives it, kept for viewers (the
// physics never reads it): a box, sphere, cylinder, capsule or mesh posed in
// the link frame, with the mesh file's resolved path and the colour of the
// element's material.
struct ModelVisualEntry {
  int geometry = 0;                     // model::GeometryType: 0 box, 1 sphere, 2 cylinder, 3 capsule, 4 mesh
  Vec3 position = Vec3::Zero();         // m: the visual's frame in the link frame
  Quat orientation = Quat::Identity();  // the visual's axes in the link frame
  Vec3 box_size = Vec3::Zero();         // m, full edge lengths
  double radius = 0.0;                  // m: sphere, cylinder, capsule
  double length = 0.0;                  // m: cylinder and capsule, along the visual's z
  std::string mesh_path;                // mesh: the resolved file (absolute)
  Vec3 mesh_scale = Vec3::Ones();       // mesh: per-axis scale from the file
  Eigen::Vector4d rgba{0.7, 0.7, 0.7, 1.0};
};

struct ModelLinkEntry {
  std::string name;                     // the file's link name
  BodyId body = 0;                      // the body that carries the link
  Vec3 position = Vec3::Zero();         // m: the link frame's origin in the body frame
  Quat orientation = Quat::Identity();  // the link frame's axes in the body frame
  std::vector<ModelVisualEntry> visuals;  // none: a viewer draws the link's collision shapes
};

struct ModelJointEntry {
  std::string name;                     // the file's joint name
  std::string type;                     // the file's joint type (revolute, fixed, ...)
  // The world joint; 0 for a fixed joint whose child was merged into its
  // parent, and for a floating joint (no constraint).
  JointId joint = 0;
  double damping = 0.0;                 // N m s/rad or N s/m, from the file
  double friction = 0.0;                // N m or N, from the file
  double effort_limit = 0.0;            // N m or N; 0: none given
  double velocity_limit = 0.0;          // rad/s or m/s; 0: none given
};

struct ModelRecord {
  ModelId id = 0;
  std::string name;                     // unique in the world
  std::string source;                   // the file path, or "<inline>"
  bool fixed_base = false;
  bool self_collide = false;
  std::vector<ModelLinkEntry> links;    // in the file's order
  std::vector<ModelJointEntry> joints;  // in the file's order
};

}  // namespace contactsim
