// The bodies of the soft step's float path (soft_wide_solver.h): a compact
// single-precision copy of what the sub-steps change, the layout Box2D v3
// and Box3D's wide solvers keep (b2BodyState: velocities, and the motion
// since the step began, which brings each contact's separation up to date
// from its anchors; soft_contact.h).
//
// WideBody holds what a contact pass reads and writes, as plain floats so
// the SIMD kernels (soft_wide_kernels.h) gather it lane by lane;
// WideBodyMotion holds what the sub-steps' integration needs besides. The
// world's double state is read once at the step's start and written once
// at its end (StoreWideBodies).
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/soft/wide/soft_wide_layout.h"
#include "service/physics/world.h"

namespace contactsim {

using wide::WideBody;

struct WideBodyMotion {
  Eigen::Vector3f accel = Eigen::Vector3f::Zero();   // F / m, m/s^2 (constant over the step)
  Eigen::Vector3f torque = Eigen::Vector3f::Zero();  // N m, world
  Eigen::Matrix3f inv_inertia = Eigen::Matrix3f::Zero();  // world, at the current orientation
  Eigen::Matrix3f R0 = Eigen::Matrix3f::Identity();       // R(q0)
  Eigen::Matrix3f inertia_body = Eigen::Matrix3f::Zero();
  Eigen::Matrix3f inv_inertia_body = Eigen::Matrix3f::Zero();
  Eigen::Quaternionf dq = Eigen::Quaternionf::Identity();  // the turn since the step's start
  float inv_mass = 0.0f;
  bool substepped = false;
  bool hold_momentum = false;  // dynamic and anisotropic: I w kept across a turn
};

// One entry per world body plus a last, resting one that padding lanes
// read and nobody writes.
struct WideBodies {
  std::vector<WideBody> state;
  std::vector<WideBodyMotion> motion;
  int dummy() const { return static_cast<int>(state.size()) - 1; }
};

// From the soft step's bodies (LoadSoftBodies) and the world's forces.
void LoadWideBodies(const World& world, const std::vector<SoftBody>& soft, ParallelRunner& runner,
                    WideBodies* bodies);
// v += h F / m, w += h I^-1 tau for the substepped dynamic bodies in [begin, end).
void IntegrateWideVelocities(float h, int begin, int end, WideBodies& bodies);
// The substepped bodies in [begin, end) moved by h at their velocities, as
// IntegrateSoftPositions moves them: the turn q <- exp(h w) q, and a
// dynamic anisotropic body's angular momentum I w kept across it.
void IntegrateWidePositions(float h, int begin, int end, WideBodies& bodies);
// Writes the step back: the soft bodies' v, w, dp and dR, and the world's
// poses x = x0 + dp, q = dq q0 (on the world's threads). The soft bodies'
// inverse inertias stay at the step's start, from which restitution's
// normal rows are made (soft_stages.cpp).
void StoreWideBodies(const WideBodies& bodies, ParallelRunner& runner, std::vector<SoftBody>& soft, World& world);

}  // namespace contactsim
