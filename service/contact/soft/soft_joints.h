// Joints in the soft step (soft_method.h): after each contact pass of a
// sub-step, the joints' exact velocity solve of contact/joints/joint_solver.h
// (a tree solve, linear in the links, so a heavy body on a light chain is
// held at once rather than over the iterations a sweep would need); after
// the step, the joints' drift is projected away (post-stabilisation, as
// under impulse). Contacts and joints thus alternate as two blocks of a
// Gauss-Seidel iteration, twice a sub-step.
#pragma once

#include <vector>

#include "service/contact/joints/joint_block.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/solver_body.h"
#include "service/physics/world.h"

namespace contactsim {

class SoftJoints {
 public:
  // Marks the dynamic bodies of every joint: they move sub-step by
  // sub-step even without a contact.
  static void MarkJointed(const World& world, std::vector<char>* substepped);

  // Where joints have damping or friction (HasJointDynamics): the
  // sub-step's joint rows with them, built once before its solve stage, so
  // that their impulses accumulate over the stage's joint passes
  // (joint_block.h) instead of being taken again at every pass.
  void Begin(const World& world, double h, const std::vector<SoftBody>& bodies);

  // The velocity solve of the world's joints over a sub-step h on the
  // bodies' v and w (the world holds the sub-step's poses). After Begin:
  // its rows in the solve stage, the joints' geometry alone in the relax
  // stage (`relax`), whose velocities only take back the positions' bias.
  void SolveVelocities(const World& world, double h, std::vector<SoftBody>& bodies, bool relax = false);

  // After the step's last sub-step: adds the impulses the drive rows
  // applied over the step, divided by world.dt, to the joints' efforts
  // (AddDriveEfforts, joints/joint_rows.h), and starts the next step's sum.
  void StoreEfforts(World& world);

 private:
  void Load(const std::vector<SoftBody>& bodies);

  std::vector<SolverBody> solver_;
  JointVelocityBlock block_;
  bool dynamics_ = false;  // Begin built block_, whose drive impulses are not yet in drive_impulses_
  std::vector<double> drive_impulses_;  // N m s or N s per joint, this step's so far
};

}  // namespace contactsim
