// The linear-time solve of a loop-free joint system, after Baraff,
// "Linear-time dynamics using Lagrange multipliers", SIGGRAPH 1996.
//
// Instead of the dense J M^-1 J^T (whose graph is dense wherever many joints
// meet one body), solve the larger but always sparse system (Baraff's eq. 9)
//   [ M   J^T ] [ dv ]   [ 0 ]
//   [ J   -R  ] [ y  ] = [ b ],    lambda = -y,
// which gives (J M^-1 J^T + R) lambda = b and dv = M^-1 J^T lambda (the same
// regularised system as the dense solver, joint_rows.h). Its graph has a
// node per dynamic body (M: 6 x 6, diag(m 1, I_world)) and per joint (R) and
// an edge per joint end: a tree when the joints make no loop. Eliminating
// every node before its parent (children first) creates no fill-in, so
// factoring (Baraff's "factor", D_i = H_ii - sum_children H_ci^T D_c^-1 H_ci)
// and solving (forward, diagonal, backward sweeps) take O(n) for n joints of
// bounded size.
//
// A joint whose other end is the world (or a static or kinematic body) has
// one neighbour; as a leaf its pivot would be R alone, near zero. Such joints
// are therefore merged into their body's node (a node of size 6 + their rows,
// factored by LU), and each tree is rooted at a body that holds the world, so
// that every remaining joint node has a body child below it and a pivot
// -(R + J D^-1 J^T) that is well conditioned.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/joints/joint_rows.h"

namespace contactsim {

// True when the joints of `blocks` make no loop through dynamic bodies.
bool JointGraphIsTree(const std::vector<JointBlock>& blocks, const std::vector<SolverBody>& bodies);

// Solves (J M^-1 J^T + R) lambda = b for the rows grouped by `blocks` (which
// cover every row). Returns false, lambda untouched, when the joints make a
// loop.
bool SolveJointsTree(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                     const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b, Eigen::VectorXd* lambda);

}  // namespace contactsim
