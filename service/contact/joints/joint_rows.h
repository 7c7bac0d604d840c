// The joints of the world as scalar constraint rows (constraint_row.h), one
// group of rows per joint (physics/joint.h gives the constraints).
//
// Velocity rows. The joint constraints C(q) = 0 must hold at the end of the
// step. Witkin and Baraff's acceleration-level condition Cddot = 0,
//   J M^-1 J^T lambda = -Jdot qdot - J M^-1 F_ext,
// integrated over a step h with the forces already in qdot* = qdot + h M^-1 F
// (impulse lambda_h = h lambda), reads
//   J M^-1 J^T lambda_h = -h Jdot qdot - J qdot*.
// The positions then move by h qdot_new (symplectic Euler). Taking the
// velocity product at half weight, J qdot_new = -(h/2) Jdot qdot, makes
// qdot_new tangent to the constraint at the MIDDLE of the step, so that
// q + h qdot_new lands on C = 0 to third order: the velocity form of SHAKE
// (Ryckaert, Ciccotti and Berendsen 1977), in which the velocities live at
// half steps and a rotating rod keeps its speed exactly. The full term
// (tangent at the end of the step) adds about (h w)^2 of the kinetic energy
// per step, w the swing rate, and no term (tangent at the start) removes as
// much: a double pendulum (w up to 9 rad/s at h = 1/240 s) then gains or
// loses tens of percent of its energy in 10 s, against 0.6% with the half
// term.
// A row's rhs holds -(h/2) Jdot qdot at the velocities it was given;
// BuildJointVelocityRows (joint_solver.h) gives it the velocity the step
// ends with, and the solver subtracts J qdot*.
//
// Rows per kind, r_A = p_A - x_A, r_B = p_B - x_B (world), lever arms of the
// anchors, and the velocity product vp = Jdot qdot of each row:
//   point (ball, hinge, fixed; 3 rows, e_k the world axes):
//     J = (e_k, r_A x e_k | -e_k, -r_B x e_k),  C_k = e_k . (p_A - p_B),
//     vp = e_k . (w_A x (w_A x r_A) - w_B x (w_B x r_B));
//   distance (1 row, divided by the length l so that it is in metres):
//     J = (d, r_A x d | -d, -r_B x d) / l,  C = (d.d - l^2) / (2 l),
//     vp = (|ddot|^2 + d . (w_A x (w_A x r_A) - w_B x (w_B x r_B))) / l;
//   hinge axis (2 rows, t_1, t_2 perpendicular to the axis a fixed in A):
//     J = (0, t_k | 0, -t_k),  C_k = t_k . (b x a) with b the axis fixed in B,
//     vp = (w_A x t_k) . (w_A - w_B);
//   weld orientation (3 rows): J = (0, e_k | 0, -e_k),
//     C = 2 vec(q_A rest q_B^-1) (the rotation vector of the misalignment for
//     small errors), vp = 0;
//   line (prismatic; 2 rows, t_1, t_2 perpendicular to the axis a fixed
//     in A): C_k = t_k . (p_A - p_B), J = (t_k, (p_B - x_A) x t_k | -t_k,
//     -r_B x t_k), vp = (w_A x (w_A x t_k)) . d + 2 (w_A x t_k) . ddot +
//     t_k . (w_A x (w_A x r_A) - w_B x (w_B x r_B)), d = p_A - p_B; then
//     the weld's 3 orientation rows;
//   joint coordinate q (hinge angle: J = (0, -a | 0, a); prismatic slide
//     s = a . (p_B - p_A): the line row of u = -a), J qdot = its rate:
//     damping (cfm = 1/(c h), rhs 0: the implicit damper), friction
//     (|lambda| <= f h, rhs 0; left out while a limit row is active), the
//     actuator's drive (below), then the limits: lower: lambda >= 0, active
//     when q would pass it within the step; rhs = min(0, (lower - q) / h),
//     so the joint may still reach the limit but not cross it
//     (speculative, as the contact methods' margins). Upper: mirrored,
//     lambda <= 0. Limits are unilateral and plastic (no bounce), as a
//     contact with restitution 0.
// The drive of an actuator with gains (physics/joint_actuator.h). Signs:
// the coordinate row's J qdot is the coordinate's rate v, and its impulse
// J^T lambda acts along the coordinate: a hinge's J = (0, -a | 0, a) turns
// A by -a lambda and B by +a lambda; a slider's line row of -a pushes B's
// anchor by +a lambda and A, at that same point, by -a lambda. Either way a
// positive lambda raises v, so lambda = u h, u the actuator's effort.
// Multiplying the implicit PD u = torque + kp (q* - q - h v') + kd (v* - v')
// by h and dividing by h (h kp + kd) gives v' + lambda / (h (h kp + kd)) =
// (kp (q* - q) + kd v*) / (h kp + kd) + torque / (h kp + kd), which is the
// solver's J qdot' + cfm lambda = rhs with
//   cfm = 1 / (h (h kp + kd)),
//   rhs = clamp((kp (q* - q) + kd v*) / (h kp + kd), +-velocity_limit)
//         + torque / (h kp + kd)
// (MakeDriveTarget): a damper of gain h kp + kd towards the target rate,
// plus the feed-forward. Bounds |lambda| <= effort_limit h make it a boxed
// compliant row, so the clamp of u is the clamp of the impulse. Like the
// damping row it has no velocity product (a rate target, not a geometric
// constraint). An actuator without gains applies its torque as a force
// (World::AccumulateForces), no row.
// The rows of a joint come in that order: equality rows, then damping and
// friction, then the drive, then limits, so that a joint's equality rows
// have the same places whatever its limits do.
// Position rows (for the projection, joint_solver.h) have the same Jacobians
// with the errors C; a limit row only when the limit is violated, C = angle -
// limit.
//
// Joints whose two bodies are both static or kinematic give no rows (nothing
// can move). A static or kinematic body keeps its solver index but has zero
// inverse mass, so ConstraintRow::Apply leaves it alone.
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"
#include "service/physics/world.h"

namespace contactsim {

// Relative regularisation of the joint systems: row k's diagonal of
// J M^-1 J^T gets kJointRegularisation times itself added (a constraint force
// mixing term, as ODE's CFM). Redundant rows (a body welded twice, a loop of
// joints) then still give a unique, bounded answer, and a consistent system
// is met to a relative 1e-10. Both solvers use it, so they agree.
constexpr double kJointRegularisation = 1e-10;

// The rows of one joint occupy rows[first, first + count).
struct JointBlock {
  JointId id = 0;
  int first = 0;
  int count = 0;
  int a = -1, b = -1;  // solver body indices; -1: the world
  int joint = -1;      // index of the joint in world.joints()
  int drive = -1;      // row index of the actuator's drive row; -1: none
};

enum class JointRowMode {
  kVelocity,  // rhs = -(h/2) Jdot qdot; limit rows when a limit would be reached within h;
              // damping and friction rows (h > 0)
  kPosition,  // error = C; limit rows only when violated; rhs unused (0); no damping or friction
  kVelocityGeometry,  // kVelocity without the damping and friction rows
};

// Appends the rows of every joint of the world, in joint id order, for the
// solver bodies `bodies` (LoadSolverBodies of the same world: indices, inverse
// masses and, in velocity mode, the velocities qdot*). h (s) is the step the
// velocity rows look ahead. `blocks` and `errors` (C per row) are optional.
void AppendJointRows(const World& world, const std::vector<SolverBody>& bodies, double h, JointRowMode mode,
                     std::vector<ConstraintRow>* rows, std::vector<JointBlock>* blocks = nullptr,
                     std::vector<double>* errors = nullptr);

// Appends the errors C of the rows AppendJointRows gives in position mode,
// in their order and equal bit for bit, without building the rows: the
// check that ends a position projection needs the errors alone.
void AppendJointErrors(const World& world, const std::vector<SolverBody>& bodies, std::vector<double>* errors);

// Sets the rhs of each block's geometry rows (its equality rows, the first
// of the block) to the velocity products at the velocities of `bodies`:
// the rhs AppendJointRows would give them there, in velocity mode, for the
// same poses and blocks.
void SetJointVelocityProducts(const World& world, const std::vector<SolverBody>& bodies, double h,
                              const std::vector<JointBlock>& blocks, std::vector<ConstraintRow>* rows);

// A mimic's row (physics/joint.h, JointMimic): C = q - m q_master - o with
// J = J_q - m J_q_master, each part the coordinate row of its joint (the
// hinge angle's or the slide's, as above), so the row spans up to four
// bodies; it is held as two two-body rows that act together. Its impulse
// mu turns the follower's coordinate by +mu and the master's by -m mu: the
// gear's torques, equal and opposite in power (Box2D's b2GearJoint).
struct CouplingRow {
  ConstraintRow follower;  // J_q of the mimic joint
  ConstraintRow master;    // -m J_q of its master
  double rhs = 0.0;        // rad/s or m/s: -(h/2) (vp - m vp_master); 0 in position mode
  double error = 0.0;      // C (rad or m; a hinge's wrapped into [-pi, pi])
  double Velocity(const std::vector<SolverBody>& s) const { return follower.Velocity(s) + master.Velocity(s); }
  void Apply(double d_lambda, std::vector<SolverBody>& s) const {
    follower.Apply(d_lambda, s);
    master.Apply(d_lambda, s);
  }
};

// Appends the row of every mimic of the world, in the follower's joint id
// order, for the solver bodies `bodies` (as AppendJointRows); a mimic whose
// four bodies are all static or kinematic gives none.
void AppendCouplingRows(const World& world, const std::vector<SolverBody>& bodies, double h, JointRowMode mode,
                        std::vector<CouplingRow>* rows);

// True when the row has a finite bound: a joint limit (one-sided), a
// joint's friction or an actuator's drive with an effort limit (boxed). A
// solver holds such a row at the bound it would pass.
inline bool IsLimitRow(const ConstraintRow& row) { return row.lo > -ConstraintRow::kInf || row.hi < ConstraintRow::kInf; }

// True when some joint of the world has damping, friction or an actuator
// with gains (a drive row).
bool HasJointDynamics(const World& world);

// Adds each drive row's impulse lambda[k] (N m s or N s) to impulses[joint]
// (resized to the world's joints when shorter).
void AddDriveImpulses(const std::vector<JointBlock>& blocks, const std::vector<double>& lambda,
                      std::vector<double>* impulses);

// Adds impulses[joint] / duration to each driven joint's effort
// (Joint::effort, which World::AccumulateForces zeroed at the step's start):
// the mean effort of the drive rows over the `duration` (s) their impulses
// span (the step, or the part of it the method solved last).
void AddDriveEfforts(const std::vector<double>& impulses, double duration, World& world);

// True for a joint's damping, friction or drive row: rows of the joint's dynamics,
// not of its geometry, which the projection of BuildJointVelocityRows
// leaves out.
inline bool IsJointDynamicsRow(const ConstraintRow& row) {
  return row.cfm > 0.0 || (row.lo > -ConstraintRow::kInf && row.hi < ConstraintRow::kInf);
}

}  // namespace contactsim
