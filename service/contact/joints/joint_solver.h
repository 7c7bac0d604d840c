// Joints in a time step, shared by the contact methods that solve contacts
// on their own (impulse, penalty): an equality-constraint velocity solve
// after the forces and contact impulses, and a projection of the positions
// back onto C = 0 after the positions moved.
//
// Velocity: the rows of joint_rows.h at the current poses and the bodies'
// velocities qdot* (forces and contact impulses included); solve
//   (J M^-1 J^T + R) lambda = rhs - J qdot*
// and add M^-1 J^T lambda (Lagrange multipliers as impulses). Limit rows
// (hinge and prismatic) are one-sided: a limit row whose lambda comes out on
// the wrong side (pulling) is dropped and the system solved again; a
// friction or drive row whose lambda passes its bound (+-f h, +-effort_limit
// h) is held there and the others solved again (active set, at most
// max_limit_passes solves). A damping or drive row carries its compliance on
// the diagonal (joint_rows.h).
//
// Drift: the velocity solve keeps C constant only to O(h^2) per step, so C
// drifts. Post-stabilisation (Cline and Pai, "Post-stabilization for rigid
// body simulation with contact and constraints", ICRA 2003) removes it after
// every step: Newton iterations on C(q) = 0 along the mass-weighted gradient,
//   (J M^-1 J^T + R) delta = -C,   x += M^-1 J^T delta (positions and
// rotations, momenta untouched),
// until every |C| is below the tolerance (quadratic convergence: 2-3
// iterations). Unlike Baumgarte stabilisation it adds no stiffness or
// parameters and leaves the velocities (and so the energy) alone, and it
// holds C to round-off, which the 1e-6 drift bound over 10 s needs.
// The last iteration is usually a chord step: when a Newton step has cut
// the largest |C| by 1e3 or more and left it within 1e3 of the tolerance,
// the next step solves with that step's factorisation (its Jacobians have
// moved by about |C| since) instead of factoring at the new poses, and cuts
// |C| by about 1e3 again; a step that cuts less makes the next a Newton step
// (the chord method: Kelley, "Iterative Methods for Linear and Nonlinear
// Equations", SIAM 1995). `chord_steps = false` factors every iteration
// (lcp: see docs/methods/lcp.md).
//
// The system is split into components (joints connected through dynamic
// bodies); a loop-free component is solved by the tree solver
// (joint_tree_solver.h), one with a loop by the dense solver
// (joint_dense_solver.h); `solver = kDense` solves everything densely.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/joints/joint_rows.h"
#include "service/contact/joints/joint_tree_solver.h"

namespace contactsim {

enum class JointSolverKind { kTree, kDense };

struct JointSolveOptions {
  JointSolverKind solver = JointSolverKind::kTree;
  int max_limit_passes = 8;             // active-set solves per velocity step at most
  int max_projection_iterations = 10;   // Newton iterations per projection at most
  double projection_tolerance = 1e-12;  // m, or rad for angular rows: largest |C| left
  bool chord_steps = true;              // a projection's Newton factorisation serves its last step (above)
  bool joint_dynamics = true;           // false: without the joints' damping and friction rows
};

struct JointStats {
  int rows = 0;                   // rows in the final velocity solve
  int limit_passes = 0;           // velocity solves (1 without active limits)
  int projection_iterations = 0;  // Newton iterations of the projection
  double max_error = 0.0;         // largest |C| after the projection (m or rad)
};

// Solves (J M^-1 J^T + R) lambda = b for rows grouped by `blocks`.
Eigen::VectorXd SolveJointSystem(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                                 const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b,
                                 JointSolverKind solver);

// The same for the rows with keep[k] only; lambda is 0 for the others.
Eigen::VectorXd SolveJointRows(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                               const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b,
                               const std::vector<char>& keep, JointSolverKind solver);

// The velocity rows of the world's joints (AppendJointRows) with the
// velocity products -(h/2) Jdot qdot taken at the velocity the step ends
// with, not at qdot*: a first solve finds that velocity without the
// products (qdot* with every geometry row at J qdot = 0 and the damping and
// drive rows at their targets) and the products are evaluated there. qdot*
// holds this step's gravity kick, which the joints cancel: a pendulum
// hanging at rest would otherwise see a "centripetal" (g h)^2 / l and creep
// (3.5e-6 m/s for 1 m at h = 1/240 s). The first solve has the velocity
// solve's matrix, so that one factorisation serves both: `factor`, when
// given, is left holding it (JointVelocityBlock). A friction row, held at
// its bound rather than at a target, or a drive whose impulse would pass
// its effort limit, makes the first solve one of the geometry rows alone.
// The LCP method takes its joint rows from here; the rows come out with
// lambda = the multipliers of that first solve (clamped to the row bounds):
// the joints' answer without contacts and velocity products, a starting
// guess for an iterative solver that has no better one (a hanging chain's
// tensions at once, where projected Gauss-Seidel from zero needs hundreds
// of sweeps).
// `mode` is kVelocity or kVelocityGeometry (without damping and friction).
void BuildJointVelocityRows(const World& world, const std::vector<SolverBody>& bodies, double h,
                            JointSolverKind solver, std::vector<ConstraintRow>* rows,
                            std::vector<JointBlock>* blocks, JointRowMode mode = JointRowMode::kVelocity,
                            JointTreeFactor* factor = nullptr);

// Sets the rows' lambda to the joints' answer alone, the active-set solve
// of ApplyJointImpulses on a copy of `bodies`: with damping and friction
// rows, which the first solve of BuildJointVelocityRows leaves at 0, the
// starting guess an iterative solver needs (a joint's friction torque acts
// on a body's spin about its centre, which projected Gauss-Seidel couples
// to the swing about the pivot only at a rate of I_cm / I_pivot a sweep).
void GuessJointImpulses(const std::vector<SolverBody>& bodies, JointSolverKind solver,
                        std::vector<ConstraintRow>* rows, const std::vector<JointBlock>& blocks);

// The velocity solve on solver bodies (LoadSolverBodies of `world`, with the
// step's forces and contact impulses already in v and w); h (s) is the step.
// The impulses are added through ConstraintRow::Apply, so dP and dL hold them.
// The drive rows' impulses are added to `drive_impulses` per joint
// (AddDriveImpulses, joint_rows.h) when given.
JointStats ApplyJointImpulses(const World& world, double h, std::vector<SolverBody>& bodies,
                              const JointSolveOptions& options = {},
                              std::vector<double>* drive_impulses = nullptr);

// The same on the world's momenta P and L; adds the drive rows' impulses
// over world.dt to the joints' efforts (AddDriveEfforts): called once a
// step, or once a sub-step of a step in sub-steps, which then add up to the
// step's mean.
JointStats SolveJointVelocities(World& world, double h, const JointSolveOptions& options = {});

// Post-stabilisation of the positions and orientations (see above).
JointStats ProjectJointPositions(World& world, const JointSolveOptions& options = {});

}  // namespace contactsim
