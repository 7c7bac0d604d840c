// A command after decoding and every check that needs no world: numbers are
// finite, sizes positive, a new body is already built, a new contact method
// already created with its parameters. Only checks against the world (does
// the body exist?) remain for the simulation thread.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "service/collision/ray_cast.h"
#include "service/contact/contact_method.h"
#include "service/model/model_builder.h"
#include "service/physics/joint.h"
#include "service/physics/rigid_body.h"
#include "service/scene/scene_spec.h"
#include "service/server/actuator_update.h"
#include "service/server/arm_driver/arm_command.h"
#include "service/server/arm_driver/wsg_command.h"
#include "service/server/journal.h"
#include "service/server/lockstep.h"

namespace contactsim {

enum class RunMode { kRealtime = 1, kFreeRun = 2, kLockstep = 3 };

// The run modes' names ("realtime", "free_run", "lockstep"), once.
struct RunModeName {
  RunMode mode;
  const char* name;
};
inline constexpr RunModeName kRunModeNames[] = {
    {RunMode::kRealtime, "realtime"}, {RunMode::kFreeRun, "free_run"}, {RunMode::kLockstep, "lockstep"}};
inline const char* NameOf(RunMode mode) {
  for (const RunModeName& m : kRunModeNames) {
    if (m.mode == mode) return m.name;
  }
  return "unknown";
}
// False for a name that is none of them.
inline bool ParseRunMode(const std::string& name, RunMode* mode) {
  for (const RunModeName& m : kRunModeNames) {
    if (name == m.name) {
      *mode = m.mode;
      return true;
    }
  }
  return false;
}

struct Command {
  enum class Kind {
    kAddBody, kRemoveBody, kSetPose, kSetVelocity, kApplyForce, kApplyImpulse, kSetMass, kSetMaterial,
    kReset, kLoadScene, kSetGravity, kSetTimestep, kSetMethod, kPause, kResume, kStep, kSetMode,
    kSnapshot, kRestore, kRewind, kRegisterController, kReleaseController, kInput,
    kAddJoint, kRemoveJoint, kSetFilter, kAddRangeSensor, kAddContactSensor, kRemoveSensor, kRayCast,
    kLoadModel, kRemoveModel, kModelInfo, kArmCommand, kWsgCommand, kSetActuators, kClearActuators, kJointStateQuery,
  };
  Kind kind = Kind::kPause;
  std::string client_id;
  int64_t request_id = 0;

  BodyId body_id = 0;                  // every body command but ADD
  RigidBody new_body;                  // ADD
  Vec3 position = Vec3::Zero();        // SET_POSE
  Quat orientation = Quat::Identity(); // SET_POSE
  Vec3 linear = Vec3::Zero();          // SET_VELOCITY (m/s), APPLY_FORCE (N), APPLY_IMPULSE (N s)
  Vec3 angular = Vec3::Zero();         // SET_VELOCITY (rad/s), APPLY_FORCE (N m)
  double duration = 0.0;               // APPLY_FORCE, s
  std::optional<Vec3> point;           // APPLY_IMPULSE
  std::optional<double> mass, density; // SET_MASS
  std::optional<double> restitution, friction;  // SET_MATERIAL
  uint32_t collision_category = 1, collision_mask = 0xFFFFFFFF;  // SET_FILTER
  int32_t collision_group = 0;
  JointSettings joint;                 // ADD joint (checked but for the bodies' existence)
  JointId joint_id = 0;                // REMOVE joint
  // LOAD model: the model as read (file and meshes), its options, and the
  // default material of its bodies; REMOVE model: its id
  std::shared_ptr<const model::ModelDescription> model;
  model::ModelOptions model_options;
  Material model_material;
  ModelId model_id = 0;
  ActuatorUpdate actuators;            // SET / CLEAR actuators (checked but against the world)

  std::shared_ptr<SceneSpec> scene;    // LOAD_SCENE
  std::string scene_path;
  Vec3 gravity = Vec3::Zero();         // SET_GRAVITY
  double dt = 0.0;                     // SET_TIMESTEP
  std::shared_ptr<ContactMethod> method;  // SET_METHOD, and LOAD_SCENE when the scene names one
  int steps = 0;                       // STEP
  RunMode mode = RunMode::kRealtime;   // SET_MODE
  double real_time_factor = 1.0;
  std::string snapshot_name;           // SNAPSHOT, RESTORE: a slot, or
  std::string snapshot_path;           //   a file
  int64_t target_step = 0;             // REWIND
  LatePolicy late_policy = LatePolicy::kWait;  // REGISTER_CONTROLLER
  double late_timeout = 0.0;           // REGISTER_CONTROLLER, s; 0 = the server's
  bool late_default = true;            // REGISTER_CONTROLLER gave no policy
  ControllerInput input;               // INPUT
  RangeSensor range_sensor;            // ADD_RANGE (checked, directions unit)
  std::string sensor_name;             // ADD_CONTACT, REMOVE sensor
  std::shared_ptr<std::vector<Ray>> rays;  // RAY_CAST (checked, directions unit)
  RayCastOptions ray_options;          // RAY_CAST
  ArmCommand arm;                      // the arm driver's command (arm_driver/arm_command.h)
  WsgCommand wsg;                      // the WSG driver's command (arm_driver/wsg_command.h)

  // ADD: said after the reply's text (a mesh's dropped triangles)
  std::string reply_note;

  // The command as it arrived (LCM-encoded), and how the journal stores it.
  std::string payload;
  RecordKind record = RecordKind::kStepTo;
};

}  // namespace contactsim
