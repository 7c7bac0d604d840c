// The bodies as the soft step sees them during one step (soft_method.h):
// velocities v and w, the inverse mass and world inverse inertia, and how
// far each body moved and turned since the step began, so that a contact's
// separation can be brought up to date from its anchors without running
// the narrowphase again (Catto, Solver2D "Soft Step", 2024: "relative
// anchors").
//
// Only bodies with a contact move sub-step by sub-step (`substepped`); the
// others fly the whole step ballistically (AdvanceBallistic), exactly as
// under every other method.
#pragma once

#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/physics/world.h"

namespace contactsim {

struct SoftBody {
  Vec3 v = Vec3::Zero();             // m/s
  Vec3 w = Vec3::Zero();             // rad/s, world
  double inv_mass = 0.0;             // 1/kg, 0 for static and kinematic bodies
  Mat3 inv_inertia = Mat3::Zero();   // world, at the current orientation
  Vec3 x0 = Vec3::Zero();            // position at the step's start
  Quat q0 = Quat::Identity();        // orientation at the step's start
  Mat3 R0t = Mat3::Identity();       // R(q0)^T
  bool isotropic = false;            // I = c 1: turning changes neither I nor w
  Vec3 dp = Vec3::Zero();            // x - x0
  Mat3 dR = Mat3::Identity();        // R(q) R(q0)^T, the turn since the step's start
  bool substepped = false;

};

// One SoftBody per world body; `substepped[i]` marks the bodies that touch
// something this step; on the world's threads (each body is its own).
void LoadSoftBodies(const World& world, const std::vector<char>& substepped, ParallelRunner& runner,
                    std::vector<SoftBody>* bodies);
// One of them.
void LoadSoftBody(const RigidBody& body, bool substepped, SoftBody* soft);

// v += h F / m and w += h I^-1 tau for the substepped dynamic bodies among
// [begin, end), or among (*order)[begin, end) when an order is given.
void IntegrateSoftVelocities(const World& world, double h, int begin, int end, std::vector<SoftBody>& bodies,
                             const std::vector<int>* order = nullptr);

// Moves the substepped bodies among [begin, end) (of `order` when given)
// by h at their velocities and brings the world inverse inertia and, with
// `track_motion`, dp and dR up to date (xpbd reads the poses themselves
// and leaves them). A dynamic body's angular momentum I w is kept across
// the turn (torque-free motion; the gyroscopic term), so w follows the new
// inertia.
void IntegrateSoftPositions(double h, int begin, int end, World& world, std::vector<SoftBody>& bodies,
                            bool track_motion = true, const std::vector<int>* order = nullptr);

// Writes P = m v and L = I w of the substepped dynamic bodies back (on the
// world's threads).
void StoreSoftBodies(const std::vector<SoftBody>& bodies, ParallelRunner& runner, World& world);

}  // namespace contactsim
