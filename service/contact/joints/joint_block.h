// The joints as one block of a block Gauss-Seidel iteration with the
// contacts (impulse solves it between its contact sweeps; soft takes the
// same turns through SoftJoints, soft_joints.h).
//
// A contact sweep changes the velocities of jointed bodies; a joint solve
// after all the sweeps then changes them again, so that the contacts'
// friction no longer holds what it was solved to hold: a box on a hinged or
// welded plank creeps a little every step, although mu holds it. Solving the
// joint rows exactly (joint_solver.h) after every sweep makes the iteration
// a block Gauss-Seidel over two blocks, joints and contacts, each solved
// given the other; it converges to the velocities that satisfy both
// (Cottle, Pang and Stone 1992, block methods for the LCP; Erleben 2007,
// "Velocity-based shock propagation for multibody dynamics animation", for
// the same split in a rigid-body solver).
//
// The rows are built once per (sub-)step; each Solve adds the increment of
// the multipliers that brings every equality row back to J v = rhs, and keeps
// each hinge limit's accumulated impulse within its bounds (a limit whose
// total would pull is held at its bound and the rest solved again).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/joints/joint_solver.h"
#include "service/contact/joints/joint_tree_solver.h"
#include "service/physics/world.h"

namespace contactsim {

class JointVelocityBlock {
 public:
  // The rows of the world's joints at the current poses, with the velocity
  // products taken from `bodies` (BuildJointVelocityRows); h (s) is the step.
  void Build(const World& world, const std::vector<SolverBody>& bodies, double h,
             JointSolverKind solver = JointSolverKind::kTree);
  // Build again at the bodies' current velocities, keeping the impulse each
  // compliant row (damping, drive) has carried so far this step: its target
  // counts that impulse (J v + cfm lambda = rhs), so a row built afresh, at
  // zero, would apply its damper or drive a second time. When nothing has
  // moved since Build (no Solve or ReadImpulses, every body's v and w the
  // same bit for bit: no contact touched a jointed body) the rows would come
  // out as they are, and are kept.
  void Rebuild(const World& world, const std::vector<SolverBody>& bodies, double h);
  // Adds the drive rows' impulses this step to `impulses` per joint
  // (AddDriveImpulses, joint_rows.h).
  void AddDriveImpulses(std::vector<double>* impulses) const;
  bool empty() const { return rows_.empty(); }
  // True when a contact joins two bodies (solver indices a, b) of one
  // jointed component: an articulated body touching itself, whose contact
  // and joint rows can ask for motions no velocity meets. Solved in turn,
  // such rows raise each other's impulses without bound (a 100-link chain
  // of mixed masses folding onto itself blew up), so a method solves the
  // joints once after its sweeps there instead.
  bool SelfContact(int a, int b) const;
  // True when solver body i is jointed.
  bool Jointed(int i) const { return i >= 0 && i < static_cast<int>(component_.size()) && component_[i] >= 0; }
  // Projects the bodies' velocities onto the joint rows and the mimics'
  // coupling rows (joint_couplings.h, with the active set the joint rows
  // chose); returns the largest row velocity error it removed (m/s or
  // rad/s).
  double Solve(std::vector<SolverBody>& bodies, int max_limit_passes = 8);
  // The rows with the impulse each has carried so far as its lambda, for a
  // direct solve of joint and contact rows together (jointed_contacts.h),
  // and the impulses that solve leaves, read back from rows[first...].
  void AppendRows(std::vector<ConstraintRow>* out) const;
  void ReadImpulses(const std::vector<ConstraintRow>& rows, size_t first);

 private:
  // The coupling rows' share of Solve; all_kept: every joint row kept (the
  // factor holds).
  double SolveCouplingRows(std::vector<SolverBody>& bodies, bool all_kept);
  std::vector<ConstraintRow> rows_;
  std::vector<JointBlock> blocks_;
  std::vector<CouplingRow> couplings_;  // the mimics' rows (joint_couplings.h)
  Eigen::VectorXd total_;  // accumulated impulse per row this step
  std::vector<int> component_;  // per solver body: its jointed component, -1 if unjointed
  JointSolverKind solver_ = JointSolverKind::kTree;
  // The rows' system factored once per Build (kTree, loop-free): every
  // Solve that keeps all rows, one per sweep, reuses it (the masses and
  // Jacobians do not change within a step, only the right-hand side).
  JointTreeFactor factor_;
  bool factored_ = false;
  Eigen::VectorXd b_, x_;
  std::vector<char> keep_;
  // Build's velocities (v, w of every body) and whether a Solve or
  // ReadImpulses has changed the totals since: Rebuild's test
  std::vector<double> built_velocities_, now_velocities_;
  bool changed_ = false;
};

}  // namespace contactsim
