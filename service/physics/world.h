// The world: bodies in ascending id order, joints in ascending id order,
// gravity, time step and clock, and timed external wrenches. Iteration order
// is the id order, so the same commands give the same state bit for bit
// (docs/architecture.md, determinism).
#pragma once

#include <map>
#include <vector>

#include "service/physics/collision_filter.h"
#include "service/physics/joint.h"
#include "service/physics/model_record.h"
#include "service/physics/rigid_body.h"
#include "service/physics/sensors.h"
#include "service/physics/sleep_settings.h"
#include "service/physics/status.h"

namespace contactsim {

struct TimedWrench {
  BodyId body = 0;
  Vec3 force = Vec3::Zero();   // N, world, at the centre of mass
  Vec3 torque = Vec3::Zero();  // N m, world
  double remaining = 0.0;      // s; a wrench with 0 acts for one step
};

class World {
 public:
  static constexpr double kDefaultDt = 1.0 / 240.0;      // s
  static Vec3 DefaultGravity() { return Vec3(0, 0, -9.81); }  // m/s^2

  // Adds a body, assigning it the next id (ids are never reused).
  BodyId AddBody(RigidBody body);
  // Removes the body, every joint attached to it (as PyBullet's removeBody
  // does), so that no joint ever refers to a missing body, and its sensors.
  Status RemoveBody(BodyId id);
  RigidBody* Find(BodyId id);
  const RigidBody* Find(BodyId id) const;
  int IndexOf(BodyId id) const;  // -1 when absent

  std::vector<RigidBody>& bodies() { return bodies_; }
  const std::vector<RigidBody>& bodies() const { return bodies_; }

  // Validates the settings (CreateJoint) and adds the joint with the next
  // joint id (ids are never reused; a separate sequence from body ids). On
  // error the world is unchanged.
  Status AddJoint(const JointSettings& settings, JointId* id);
  Status RemoveJoint(JointId id);
  const Joint* FindJoint(JointId id) const;
  // Replaces a joint's actuator (joint_actuator.h) and wakes its bodies.
  // NotFound for an unknown id, InvalidArgument for a bad value, and
  // FailedPrecondition for a kind without a joint coordinate (distance,
  // ball, fixed); on error the joint is unchanged.
  Status SetJointActuator(JointId id, const JointActuator& actuator);
  const std::vector<Joint>& joints() const { return joints_; }
  // Makes joint `follower` a mimic of mimic.master (joint.h, JointMimic):
  // both hinges or both sliders, not the same joint, no cycle of mimics,
  // a finite multiplier and offset; master 0 removes the mimic. NotFound
  // for an unknown id, InvalidArgument for the rest, the message naming the
  // joints and the value; on error nothing changes. Removing the master
  // (or a body under it) removes the mimic.
  Status SetJointMimic(JointId follower, const JointMimic& mimic);
  // True when some joint is a mimic.
  bool HasJointMimics() const;
  // Records the effort the actuator of joints()[index] applied in the step
  // (Joint::effort): the contact method writes it, clamped as applied.
  void SetJointEffort(size_t index, double effort) { joints_[index].effort = effort; }
  // The body pairs whose joints exclude their contacts (collide_connected
  // false), kept in step with the joints: ShouldCollide's third argument.
  const JointPairSet& joined_pairs() const { return joined_; }

  // Replaces a body's collision filter (collision_filter.h) and wakes its
  // island: what rested on it through a pair that is now filtered falls.
  // NotFound for an unknown id (0 is the world, which has no filter).
  Status SetCollisionFilter(BodyId id, uint32_t category, uint32_t mask, int32_t group);

  // Adds a wrench and wakes the body's island (a force is never lost to sleep).
  void AddWrench(const TimedWrench& wrench);
  const std::vector<TimedWrench>& wrenches() const { return wrenches_; }
  // Replaces the content with saved bodies (ids ascending, each < next_id)
  // and wrenches, as a snapshot holds them; on error nothing changes.
  Status Assign(std::vector<RigidBody> bodies, std::vector<TimedWrench> wrenches, BodyId next_id);
  // Replaces the joints with saved ones (ids ascending, each < next, bodies
  // present, mimics valid as SetJointMimic checks them), as a snapshot
  // holds them; on error nothing changes.
  Status AssignJoints(std::vector<Joint> joints, JointId next);
  // Sets each body's force and torque to gravity plus the active wrenches,
  // plus the feed-forward effort of every actuator without gains (kp = kd =
  // 0, ActuatorFeedForward in joint_actuator.h), clamped to its effort limit
  // and recorded as the joint's effort; an actuator with gains is a drive
  // row of the contact method, which records its effort after the step.
  void AccumulateForces();
  // Advances the clock by dt, ages the wrenches and drops expired ones.
  void FinishStep();

  // Empties the world and restarts the clock; gravity and dt to defaults.
  // The sleep settings stay: they are the run's, not the content's.
  void Clear();

  // Sleeping (docs/physics.md, "Sleeping"). Waking clears the island label
  // and the rest timer of every body of the island (they keep the pose and
  // the zero momenta they slept with); waking an awake body restarts its
  // rest timer, so a changed body stays awake for at least
  // sleep.time_to_sleep. Adding or removing a body's joint, removing the
  // body and adding a wrench on it wake it here.
  void WakeBody(BodyId id);
  void WakeIsland(BodyId island);
  void WakeAll();
  int SleepingCount() const;

  Vec3 gravity = DefaultGravity();
  double dt = kDefaultDt;
  double time = 0.0;     // s
  int64_t step = 0;      // steps taken
  BodyId next_id = 1;
  JointId next_joint_id = 1;
  SleepSettings sleep;
  Sensors sensors;  // not part of the state hash: they read the world, never change it
  // The robot models the world holds (model_record.h), in the order they
  // were added, and the id the next one gets. Kept with the world, not in
  // the state hash.
  std::vector<ModelRecord> models;
  ModelId next_model_id = 1;

 private:
  void Reindex();
  // The feed-forward effort of an actuator without gains (AccumulateForces).
  void ApplyFeedForward(Joint& joint);
  void IndexJointPairs();
  // Drops the mimics whose master is gone.
  void DropOrphanMimics();
  std::vector<RigidBody> bodies_;
  std::map<BodyId, int> index_;
  std::vector<TimedWrench> wrenches_;
  std::vector<Joint> joints_;
  JointPairSet joined_;
};

// 64-bit FNV-1a hash over every body's id and state bits (x, q, P, L), every
// joint (id, kind, bodies, anchors, axes, rest pose, length, limits) and the
// clock: equal hashes mean bit-identical worlds. A world without joints
// hashes as it did before joints existed; with sleep enabled each body's
// rest timer and island label follow its state bits (with sleep off they
// are never set, and the hash is what it was before sleeping existed). A
// joint that lets its bodies touch adds that flag, and an actuated joint
// (IsActuated) its actuator's fields, a mimic its master, multiplier and
// offset; the defaults add nothing.
uint64_t HashWorldState(const World& world);

// Total kinetic energy of the dynamic bodies (J): sum of |P|^2 / 2m + L.w / 2.
double KineticEnergy(const World& world);
// Gravitational potential energy of the dynamic bodies (J), zero at the
// origin: V = -sum m g . x, so that T + V is conserved in free flight.
double PotentialEnergy(const World& world);

}  // namespace contactsim
