// A simulated arm's joints in the world: the model's first hinges in the
// model's joint order (the file's), their coordinates and rates, the
// torques that hold the arm against gravity, and the compensation of its
// weight. The arm is looked up by its model's name each time, so a world
// replaced by RESET, RESTORE or REWIND is always the one read.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "service/physics/model_record.h"
#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

struct ArmJoints {
  ModelId model = 0;
  std::vector<JointId> joints;               // the arm's hinges, in order
  // Per joint, the dynamic bodies it carries: its child body and every body
  // reached from there through the model's joints without passing its parent.
  std::vector<std::vector<BodyId>> outboard;
  std::vector<double> effort_limit;          // N m, from the file; infinity when none given
  std::vector<double> velocity_limit;        // rad/s, likewise
  std::vector<BodyId> bodies;                // every dynamic body of the model
};

// A model file's effort or velocity limit (ModelJointEntry: 0 when none
// was given) as a drive's limit: infinity for none.
double LimitOrInfinity(double limit);

// The model of that name in the world, or null.
const ModelRecord* FindModelNamed(const World& world, const std::string& name);

// The first `count` hinge joints of the model named `model`. NotFound when
// the world holds no such model, FailedPrecondition when it has fewer hinges.
Status FindArmJoints(const World& world, const std::string& model, int count, ArmJoints* out);

// Each joint's angle (rad, in (-pi, pi]) and rate (rad/s): JointPosition and
// JointVelocity (physics/joint.h).
void ReadArmJoints(const World& world, const ArmJoints& arm, std::vector<double>* position,
                   std::vector<double>* velocity);

// A force (N, through the centre of mass) and a torque (N m) on one body.
struct BodyLoad {
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

// The torque about each joint's axis of the loads on the bodies it carries
// (N m): tau_i = a_i . sum_b ((x_b - p_i) x F_b + T_b), with a_i the axis and
// p_i the anchor in the world and load(b) = (F_b, T_b).
std::vector<double> JointAxisTorques(const World& world, const ArmJoints& arm,
                                     const std::function<BodyLoad(BodyId)>& load);

// The torque each drive must apply to hold the arm still against gravity
// (N m): tau_i = -a_i . sum_b (x_b - p_i) x (m_b g) over the bodies b that
// joint i carries, with a_i its axis and p_i its anchor in the world (the
// static balance of a serial chain, Craig, "Introduction to Robotics",
// sec. 5.9, "Static forces in manipulators").
std::vector<double> GravityHoldTorques(const World& world, const ArmJoints& arm);

// Adds a force -m g at each of the arm's bodies' centres of mass for the
// next step. For an arm on a fixed base this is the generalized force
// J^T (-m g) summed over the bodies, i.e. exactly the joint torques
// GravityHoldTorques gives, applied without passing through the drives.
void CompensateGravity(const ArmJoints& arm, World* world);

}  // namespace contactsim
