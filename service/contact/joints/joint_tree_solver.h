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
#include <array>
#include <vector>

#include "service/contact/joints/joint_rows.h"

namespace contactsim {

// The factored system, solved for any number of right-hand sides. Every node's
// blocks live in fixed-size arrays of at most kMaxNodeRows rows, stored row by
// row at the node's own size, and are factored by plain loops (small_lu.h),
// so factoring and solving allocate nothing on the heap for them.
class JointTreeFactor {
 public:
  // A body's 6 plus the rows of its joints to the world, or one joint's
  // rows: 24 holds a body with two joints of every row kind. A larger node
  // is refused (Factor returns false) and its system solved densely.
  static constexpr int kMaxNodeRows = 24;
  using NodeBlock = std::array<double, kMaxNodeRows * kMaxNodeRows>;
  // A node of Baraff's graph: a dynamic body with its joints to the world,
  // or a joint between two dynamic bodies.
  struct Node {
    int body = -1;            // solver body index; -1 for a joint node
    std::vector<int> blocks;  // body: its world joints; joint: the one block
    int dim = 0;              // 6 + world-joint rows, or the joint's rows
    std::vector<int> links;   // neighbouring nodes
    int parent = -1;
    // H(i, parent) is dim x dim(parent), zero outside its first lead_rows
    // rows and lead_cols columns: a joint's rows act on a body's velocity
    // block only (its first 6 entries), never on its world joints' rows.
    // H and J = D^-1 H hold those columns only (row stride lead_cols).
    int lead_rows = 0, lead_cols = 0;
    NodeBlock D;              // H_ii (dim x dim), then the pivot D_i, then its LU factors
    std::array<int, kMaxNodeRows> pivots;
    NodeBlock H;              // H(i, parent)
    NodeBlock J;              // D^-1 H(i, parent)
    std::array<double, kMaxNodeRows> x;
  };

  // Factors (J M^-1 J^T + R) of the rows grouped by `blocks`; false when the
  // joints make a loop or a node has more than kMaxNodeRows rows. A system
  // equal bit for bit to the one factored last (the same rows' Jacobians and
  // compliance, the same blocks, their bodies' inverse masses and inertias)
  // keeps that factorisation: a step builds its joint rows again at new
  // velocities but the same poses (JointVelocityBlock::Rebuild), which
  // changes only the right-hand sides. `reuse = false` skips that
  // comparison (and the key it needs) for a caller whose systems do not
  // repeat; the factors are the same either way.
  bool Factor(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
              const std::vector<SolverBody>& bodies, bool reuse = true);
  // lambda for the right-hand side b (one entry per row), after Factor with
  // the same blocks.
  void Solve(const std::vector<JointBlock>& blocks, const Eigen::VectorXd& b, Eigen::VectorXd* lambda);

 private:
  bool Build(const std::vector<SolverBody>& bodies);
  // Writes into key_next_ every input of the factorisation.
  void Key(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
           const std::vector<SolverBody>& bodies);
  int NewNode(int body, int dim);
  int BodyNode(int body);
  void Order(const std::vector<SolverBody>& bodies);
  void Diagonal(const std::vector<SolverBody>& bodies, Node* n) const;
  void Coupling(const Node& parent, Node* n) const;
  void Eliminate(Node* n, Node* parent) const;

  const std::vector<ConstraintRow>* rows_ = nullptr;  // while factoring
  const std::vector<JointBlock>* blocks_ = nullptr;
  int row_count_ = 0;
  // nodes_[0, count_) are this system's. A node's storage (three fixed-size
  // blocks, some 14 kB) is kept for the next system: constructing one
  // value-initialises, that is zeroes, all of it, which cost more than the
  // factorisation itself.
  std::vector<Node> nodes_;
  int count_ = 0;
  std::vector<int> node_of_body_;
  std::vector<int> preorder_;  // parents before children
  std::vector<char> seen_;     // Order's scratch, kept for the next system
  std::vector<int> members_, stack_;
  std::vector<double> key_, key_next_;  // the factored system's inputs
  bool keyed_ = false;                   // key_ holds the factors' inputs
  // The graph's inputs (the bodies' count, each block's rows and ends and
  // whether they are dynamic) when Build last ran, and its answer: a system
  // of the same shape keeps the graph
  std::vector<int> shape_, shape_next_;
  bool shape_ok_ = false;
};

// True when the joints of `blocks` make no loop through dynamic bodies.
bool JointGraphIsTree(const std::vector<JointBlock>& blocks, const std::vector<SolverBody>& bodies);

// Solves (J M^-1 J^T + R) lambda = b for the rows grouped by `blocks` (which
// cover every row). Returns false, lambda untouched, when the joints make a
// loop or a node is too large (JointTreeFactor).
bool SolveJointsTree(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                     const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b, Eigen::VectorXd* lambda);

}  // namespace contactsim
