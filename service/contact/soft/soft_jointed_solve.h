// The soft step's contacts on jointed bodies (jointed_contacts.h;
// docs/physics.md, "Jointed supports").
//
// The soft step alternates its contact passes with the joints' exact solve
// (soft_joints.h) joint_passes times a stage, a block Gauss-Seidel that
// meets a heavy load on a light jointed plank at about m_plank / m_load a
// turn: 50 kg on a 0.5 kg hinged plank crept 31 mm in 3 s and swung 2.8
// degrees too far. So after the last contact pass of each solve and relax
// stage, the points on jointed bodies and the rows of the joints that hold
// them are solved together by the subspace solve (subspace_solve.h), the
// points' rows aiming where the pass aimed (their springs' compliance
// included: SoftPointRows) and the joint rows at the sub-step's poses with
// the joints' geometry alone (their damping and friction rows stay with the
// joint solve after it). Worlds without joints, and worlds where a jointed
// body touches its own component, are untouched.
//
// Friction spread by load. A face's four points hold eight friction rows
// for three motions (two slides and the twist about n), so A is singular
// there and the minimum-norm solve spreads a stuck face's friction evenly
// over its points whatever their loads. On a slope a box's uphill corners
// carry a sixth of its weight (the tipping moment), their even share passes
// their cone, and the feasible steps hold one row a pass: five 10 kg boxes
// used all 16 passes in nearly every solve stage and crept 5-19 mm in 3 s.
// So each friction row gets the compliance
//   cfm = c / (mu lambda_n),  c = kFrictionSlip,
// lambda_n its point's normal impulse from this solve's last call (the warm
// start at a step's first): the solve, J v + cfm lambda = rhs, then picks of
// the friction that holds the face the one that minimises
// sum lambda_t^2 / (mu lambda_n), friction in proportion to the points'
// loads, inside every cone whenever the face's total is inside mu N (a
// sticking point's friction is at most mu lambda_n, so it slips at most c).
// The same boxes then take 1.06 passes a solve on average and creep
// 0.10-0.23 mm (docs/methods/soft.md, "Jointed supports").
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/joints/joint_rows.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/subspace_solve.h"
#include "service/physics/world.h"

namespace contactsim {

class SoftJointedSolve {
 public:
  // Selects the points on jointed dynamic bodies; `options` as the
  // heavy-on-light solve's (soft_ratio_solve.h), for every mass ratio.
  void Prepare(const World& world, const SubspaceOptions& options, const std::vector<SoftBody>& bodies,
               const std::vector<SoftPoint>& points);
  bool active() const { return !selected_.empty(); }
  // After a pass of sub-step h: the selected points' rows and the joint rows
  // solved together (the world holds the sub-step's poses).
  void Solve(const World& world, double h, const SoftPass& pass, std::vector<SoftPoint>& points,
             std::vector<SoftBody>& bodies);

 private:
  SubspaceOptions options_;
  std::vector<int> selected_;        // point indices, ascending
  std::vector<double> load_;         // N s per selected point: its last normal impulse (friction spread by load)
  std::vector<char> marked_;         // per world body: jointed and touched
  std::vector<SolverBody> solver_;   // per world body
  std::vector<ConstraintRow> rows_;  // per selected point: normal, t1, t2; then the joint rows
  std::vector<ConstraintRow> joint_rows_;
  std::vector<JointBlock> joint_blocks_;
  SubspaceSolver subspace_;
};

}  // namespace contactsim
