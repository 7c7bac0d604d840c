// Turns a robot model description (model_description.h) into the bodies and
// joints the world adds, every one checked before anything is added, so a
// load is atomic: the whole model or none of it. docs/models.md, "What the
// builder does", gives the rules and why:
//
//   * a link with mass becomes a dynamic body with the file's mass, centre
//     of mass and full inertia; its collision elements are the body's shapes
//     (box, sphere, capsule, cylinder as a convex hull, a mesh as the convex
//     hull of its vertices);
//   * a link held by a fixed joint is merged into its parent's body (masses,
//     centres and inertias combined, shapes kept at their offsets), as
//     pinocchio, Drake and MuJoCo treat a weld: exact, and no stiff joint
//     rows between two bodies that never move relative to each other;
//   * a link without <inertial> gets PyBullet's default, 1 kg with a unit
//     diagonal inertia at the link origin, unless it is merged into a body
//     with mass or is the fixed base;
//   * revolute -> hinge (with its limits), continuous -> hinge, prismatic ->
//     prismatic, floating -> no joint, planar -> refused; a hinge's or
//     slider's actuator takes the file's effort and velocity limits (gains
//     0: it drives nothing until a command sets them); a <mimic> makes the
//     joint a mimic of its master (physics/joint.h, JointMimic);
//   * every pose at q = 0 from the joint origins (forward kinematics from the
//     root, placed at the base pose); links joined by a joint never collide,
//     and self-collision off puts the model's bodies in one collision group
//     that never collides with itself.
#pragma once

#include <string>
#include <vector>

#include "service/model/model_description.h"
#include "service/physics/body_settings.h"
#include "service/physics/hull_vertex_budget.h"
#include "service/physics/joint.h"
#include "service/physics/model_record.h"
#include "service/physics/status.h"

namespace contactsim::model {

struct ModelOptions {
  std::string name;                 // the model's name in the world; empty: the description's
  Pose base;                        // the root link's frame in the world
  bool fixed_base = false;          // the root link is static
  bool self_collide = false;        // the model's links not joined by a joint collide with each other
  // Each collision mesh becomes the convex hull of at most this many of its
  // vertices (at least 4; hull_vertex_budget.h, docs/models.md "Hull vertex
  // budget"); 0: the full hull of every vertex.
  int max_hull_vertices = kDefaultMaxHullVertices;
};

// One body of the built model: a link, with any links merged into it.
struct BuiltBody {
  int link = -1;                    // the owning link's index in the description
  BodySettings settings;            // pose at q = 0 in the world
};

// One world joint of the built model, between two of its bodies.
struct BuiltJoint {
  int joint = -1;                   // index in the description's joints
  int body_a = -1, body_b = -1;     // indices into ModelBuild::bodies (parent, child)
  JointSettings settings;           // body ids left 0 until the bodies exist
  JointActuator actuator;           // the file's effort and velocity limits, no gains (MakeJointActuator)
  // A mimic: the index into ModelBuild::joints of its master (-1: none), and
  // the multiplier and offset, set on the world joints once they exist
  int mimic_of = -1;
  JointMimic mimic;                 // master left 0 until the joints exist
};

struct ModelBuild {
  std::vector<BuiltBody> bodies;
  std::vector<BuiltJoint> joints;
  // For every link in the file's order: its body (index into bodies) and its
  // world pose at q = 0, from which the record's link frames are taken once
  // the bodies exist.
  std::vector<int> link_body;
  std::vector<Pose> link_pose_W;
  ModelRecord record;               // names, types, dynamics; ids filled when added
};

// Checks the description (model_check.h) and builds every body's and
// joint's settings. Errors name the model and the link or joint; on error
// *build is untouched.
Status BuildModel(ModelDescription description, const ModelOptions& options, ModelBuild* build);

}  // namespace contactsim::model
