#include "service/contact/joints/joint_tree_solver.h"

#include <Eigen/LU>
#include <utility>

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

bool Dynamic(int index, const std::vector<SolverBody>& bodies) {
  return index >= 0 && bodies[index].inv_mass > 0.0;
}

// A node of Baraff's graph: a dynamic body with its joints to the world, or
// a joint between two dynamic bodies.
struct Node {
  int body = -1;             // solver body index; -1 for a joint node
  std::vector<int> blocks;   // body: its world joints; joint: the one block
  int dim = 0;               // 6 + world-joint rows, or the joint's rows
  std::vector<int> links;    // neighbouring nodes
  int parent = -1;
  MatrixXd H_parent;         // H(i, parent): dim x dim(parent)
  MatrixXd J;                // D^-1 H(i, parent)
  Eigen::PartialPivLU<MatrixXd> D;
  VectorXd x;
};

// J of `row` on the side that is `body`, as (lin, ang)
Eigen::Matrix<double, 1, 6> RowOn(const ConstraintRow& row, int body) {
  Eigen::Matrix<double, 1, 6> j;
  if (row.a == body) {
    j << row.lin_a.transpose(), row.ang_a.transpose();
  } else {
    j << row.lin_b.transpose(), row.ang_b.transpose();
  }
  return j;
}

class TreeSystem {
 public:
  TreeSystem(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
             const std::vector<SolverBody>& bodies)
      : rows_(rows), blocks_(blocks), bodies_(bodies) {}

  // Builds the graph; false when it has a loop.
  bool Build();
  void Factor();
  VectorXd Solve(const VectorXd& b);

 private:
  int BodyNode(int body);
  MatrixXd Diagonal(const Node& n) const;
  // H(joint node, body node): the joint's rows on the body's velocity block
  MatrixXd Coupling(const Node& joint, const Node& body) const;
  void Order();

  const std::vector<ConstraintRow>& rows_;
  const std::vector<JointBlock>& blocks_;
  const std::vector<SolverBody>& bodies_;
  std::vector<Node> nodes_;
  std::vector<int> node_of_body_;
  std::vector<int> preorder_;  // parents before children
};

int TreeSystem::BodyNode(int body) {
  if (node_of_body_[body] < 0) {
    node_of_body_[body] = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.back().body = body;
    nodes_.back().dim = 6;
  }
  return node_of_body_[body];
}

bool TreeSystem::Build() {
  node_of_body_.assign(bodies_.size(), -1);
  UnionFind sets(static_cast<int>(bodies_.size()));
  for (int k = 0; k < static_cast<int>(blocks_.size()); ++k) {
    const JointBlock& blk = blocks_[k];
    const bool da = Dynamic(blk.a, bodies_), db = Dynamic(blk.b, bodies_);
    if (da && db) {
      if (!sets.Join(blk.a, blk.b)) return false;  // already connected: a loop
      const int na = BodyNode(blk.a), nb = BodyNode(blk.b);
      const int nj = static_cast<int>(nodes_.size());
      nodes_.emplace_back();
      nodes_[nj].blocks = {k};
      nodes_[nj].dim = blk.count;
      nodes_[nj].links = {na, nb};
      nodes_[na].links.push_back(nj);
      nodes_[nb].links.push_back(nj);
    } else {
      Node& n = nodes_[BodyNode(da ? blk.a : blk.b)];
      n.blocks.push_back(k);
      n.dim += blk.count;
    }
  }
  Order();
  return true;
}

// Roots each tree at its first body (solver order) that holds the world,
// else at its first body, and lists the nodes parents first (iterative DFS).
void TreeSystem::Order() {
  std::vector<bool> seen(nodes_.size(), false);
  for (int body = 0; body < static_cast<int>(bodies_.size()); ++body) {
    const int start = node_of_body_[body];
    if (start < 0 || seen[start]) continue;
    std::vector<int> members = {start};
    seen[start] = true;
    for (size_t m = 0; m < members.size(); ++m) {
      for (int l : nodes_[members[m]].links) {
        if (!seen[l]) seen[l] = true, members.push_back(l);
      }
    }
    auto key = [this](int i) { return std::make_pair(nodes_[i].blocks.empty(), nodes_[i].body); };
    int root = start;
    for (int i : members) {
      if (nodes_[i].body >= 0 && key(i) < key(root)) root = i;
    }
    std::vector<int> stack = {root};
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      preorder_.push_back(i);
      for (int l : nodes_[i].links) {
        if (l == nodes_[i].parent) continue;
        nodes_[l].parent = i;
        stack.push_back(l);
      }
    }
  }
}

MatrixXd TreeSystem::Diagonal(const Node& n) const {
  MatrixXd H = MatrixXd::Zero(n.dim, n.dim);
  int r = 0;
  if (n.body >= 0) {
    const SolverBody& s = bodies_[n.body];
    H.topLeftCorner<3, 3>() = Mat3::Identity() / s.inv_mass;
    H.block<3, 3>(3, 3) = s.inv_inertia.inverse();
    r = 6;
  }
  for (int k : n.blocks) {
    const JointBlock& blk = blocks_[k];
    for (int i = 0; i < blk.count; ++i, ++r) {
      const ConstraintRow& row = rows_[blk.first + i];
      if (n.body >= 0) {
        const auto j = RowOn(row, n.body);
        H.block<1, 6>(r, 0) = j;
        H.block<6, 1>(0, r) = j.transpose();
      }
      H(r, r) = -kJointRegularisation * row.Diagonal(bodies_) - row.cfm;  // R: regularisation and compliance
    }
  }
  return H;
}

MatrixXd TreeSystem::Coupling(const Node& joint, const Node& body) const {
  const JointBlock& blk = blocks_[joint.blocks[0]];
  MatrixXd H = MatrixXd::Zero(joint.dim, body.dim);
  for (int i = 0; i < blk.count; ++i) H.block<1, 6>(i, 0) = RowOn(rows_[blk.first + i], body.body);
  return H;
}

void TreeSystem::Factor() {
  std::vector<MatrixXd> D(nodes_.size());
  for (size_t i = 0; i < nodes_.size(); ++i) D[i] = Diagonal(nodes_[i]);
  // children before parents: D_p -= H(i,p)^T D_i^-1 H(i,p)
  for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
    Node& n = nodes_[*it];
    n.D.compute(D[*it]);
    if (n.parent < 0) continue;
    const Node& p = nodes_[n.parent];
    n.H_parent = n.body >= 0 ? MatrixXd(Coupling(p, n).transpose()) : Coupling(n, p);
    n.J = n.D.solve(n.H_parent);
    D[n.parent].noalias() -= n.H_parent.transpose() * n.J;
  }
}

VectorXd TreeSystem::Solve(const VectorXd& b) {
  for (Node& n : nodes_) {
    n.x = VectorXd::Zero(n.dim);
    int r = n.body >= 0 ? 6 : 0;
    for (int k : n.blocks) {
      const JointBlock& blk = blocks_[k];
      n.x.segment(r, blk.count) = b.segment(blk.first, blk.count);
      r += blk.count;
    }
  }
  // forward (children first), diagonal, backward (parents first)
  for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
    const Node& n = nodes_[*it];
    if (n.parent >= 0) nodes_[n.parent].x.noalias() -= n.J.transpose() * n.x;
  }
  for (Node& n : nodes_) n.x = n.D.solve(n.x);
  for (int i : preorder_) {
    Node& n = nodes_[i];
    if (n.parent >= 0) n.x.noalias() -= n.J * nodes_[n.parent].x;
  }
  VectorXd lambda = VectorXd::Zero(b.size());
  for (const Node& n : nodes_) {
    int r = n.body >= 0 ? 6 : 0;
    for (int k : n.blocks) {
      const JointBlock& blk = blocks_[k];
      lambda.segment(blk.first, blk.count) = -n.x.segment(r, blk.count);
      r += blk.count;
    }
  }
  return lambda;
}

}  // namespace

bool JointGraphIsTree(const std::vector<JointBlock>& blocks, const std::vector<SolverBody>& bodies) {
  UnionFind sets(static_cast<int>(bodies.size()));
  for (const JointBlock& blk : blocks) {
    if (Dynamic(blk.a, bodies) && Dynamic(blk.b, bodies) && !sets.Join(blk.a, blk.b)) return false;
  }
  return true;
}

bool SolveJointsTree(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                     const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b, Eigen::VectorXd* lambda) {
  TreeSystem system(rows, blocks, bodies);
  if (!system.Build()) return false;
  system.Factor();
  *lambda = system.Solve(b);
  return true;
}

}  // namespace contactsim
