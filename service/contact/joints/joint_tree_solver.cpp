#include "service/contact/joints/joint_tree_solver.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "service/contact/union_find.h"

namespace contactsim {
namespace {

using NodeMatrix = JointTreeFactor::NodeMatrix;
using NodeVector = JointTreeFactor::NodeVector;
using Node = JointTreeFactor::Node;
constexpr int kMaxNodeRows = JointTreeFactor::kMaxNodeRows;

bool Dynamic(int index, const std::vector<SolverBody>& bodies) {
  return index >= 0 && bodies[index].inv_mass > 0.0;
}

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

}  // namespace

// A node in the next slot, reusing its storage when an earlier system had one.
int JointTreeFactor::NewNode(int body, int dim) {
  if (count_ == static_cast<int>(nodes_.size())) nodes_.emplace_back();
  Node& n = nodes_[count_];
  n.body = body;
  n.blocks.clear();
  n.dim = dim;
  n.links.clear();
  n.parent = -1;
  return count_++;
}

int JointTreeFactor::BodyNode(int body) {
  if (node_of_body_[body] < 0) node_of_body_[body] = NewNode(body, 6);
  return node_of_body_[body];
}

bool JointTreeFactor::Build(const std::vector<SolverBody>& bodies) {
  count_ = 0;
  preorder_.clear();
  node_of_body_.assign(bodies.size(), -1);
  UnionFind sets(static_cast<int>(bodies.size()));
  for (int k = 0; k < static_cast<int>(blocks_->size()); ++k) {
    const JointBlock& blk = (*blocks_)[k];
    const bool da = Dynamic(blk.a, bodies), db = Dynamic(blk.b, bodies);
    if (da && db) {
      if (!sets.Join(blk.a, blk.b)) return false;  // already connected: a loop
      const int na = BodyNode(blk.a), nb = BodyNode(blk.b);
      const int nj = NewNode(-1, blk.count);  // may move the nodes: indices only across it
      nodes_[nj].blocks.push_back(k);
      nodes_[nj].links.push_back(na);
      nodes_[nj].links.push_back(nb);
      nodes_[na].links.push_back(nj);
      nodes_[nb].links.push_back(nj);
    } else {
      const int i = BodyNode(da ? blk.a : blk.b);
      nodes_[i].blocks.push_back(k);
      nodes_[i].dim += blk.count;
    }
  }
  for (int i = 0; i < count_; ++i) {
    if (nodes_[i].dim > kMaxNodeRows) return false;  // too large for the fixed-size blocks
  }
  Order(bodies);
  return true;
}

// Roots each tree at its first body (solver order) that holds the world,
// else at its first body, and lists the nodes parents first (iterative DFS).
void JointTreeFactor::Order(const std::vector<SolverBody>& bodies) {
  std::vector<char>& seen = seen_;
  std::vector<int>& members = members_;
  std::vector<int>& stack = stack_;
  seen.assign(count_, 0);
  for (int body = 0; body < static_cast<int>(bodies.size()); ++body) {
    const int start = node_of_body_[body];
    if (start < 0 || seen[start]) continue;
    members.assign(1, start);
    seen[start] = 1;
    for (size_t m = 0; m < members.size(); ++m) {
      for (int l : nodes_[members[m]].links) {
        if (!seen[l]) seen[l] = 1, members.push_back(l);
      }
    }
    auto key = [this](int i) { return std::make_pair(nodes_[i].blocks.empty(), nodes_[i].body); };
    int root = start;
    for (int i : members) {
      if (nodes_[i].body >= 0 && key(i) < key(root)) root = i;
    }
    stack.assign(1, root);
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

void JointTreeFactor::Diagonal(const Node& n, const std::vector<SolverBody>& bodies, NodeMatrix* H) const {
  const std::vector<ConstraintRow>& rows = *rows_;
  H->setZero(n.dim, n.dim);
  int r = 0;
  if (n.body >= 0) {
    const SolverBody& s = bodies[n.body];
    H->topLeftCorner<3, 3>() = Mat3::Identity() / s.inv_mass;
    H->block<3, 3>(3, 3) = s.inv_inertia.inverse();
    r = 6;
  }
  for (int k : n.blocks) {
    const JointBlock& blk = (*blocks_)[k];
    for (int i = 0; i < blk.count; ++i, ++r) {
      const ConstraintRow& row = rows[blk.first + i];
      if (n.body >= 0) {
        const auto j = RowOn(row, n.body);
        H->block<1, 6>(r, 0) = j;
        H->block<6, 1>(0, r) = j.transpose();
      }
      (*H)(r, r) = -kJointRegularisation * row.Diagonal(bodies) - row.cfm;  // R: regularisation and compliance
    }
  }
}

// H(joint node, body node): the joint's rows on the body's velocity block
void JointTreeFactor::Coupling(const Node& joint, const Node& body, NodeMatrix* H) const {
  const JointBlock& blk = (*blocks_)[joint.blocks[0]];
  H->setZero(joint.dim, body.dim);
  for (int i = 0; i < blk.count; ++i) H->block<1, 6>(i, 0) = RowOn((*rows_)[blk.first + i], body.body);
}

// Indices are stored as doubles (exact below 2^53); a row stores its
// bodies' masses and inertias, so that the key needs no body list.
void JointTreeFactor::Key(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                          const std::vector<SolverBody>& bodies) {
  constexpr size_t kPerBlock = 4, kPerRow = 3 + 12 + 2 * 10;
  key_next_.resize(1 + kPerBlock * blocks.size() + kPerRow * rows.size());
  double* k = key_next_.data();
  *k++ = static_cast<double>(bodies.size());
  for (const JointBlock& blk : blocks) {
    *k++ = blk.first;
    *k++ = blk.count;
    *k++ = blk.a;
    *k++ = blk.b;
  }
  auto put = [&k](const double* v, int n) { k = std::copy(v, v + n, k); };
  auto body = [&](int i) {
    if (i < 0) {
      k = std::fill_n(k, 10, 0.0);  // the world
      return;
    }
    *k++ = bodies[i].inv_mass;
    put(bodies[i].inv_inertia.data(), 9);
  };
  for (const ConstraintRow& row : rows) {
    *k++ = row.a;
    *k++ = row.b;
    *k++ = row.cfm;
    for (const Vec3* v : {&row.lin_a, &row.ang_a, &row.lin_b, &row.ang_b}) put(v->data(), 3);
    body(row.a);
    body(row.b);
  }
}

bool JointTreeFactor::Factor(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                             const std::vector<SolverBody>& bodies) {
  Key(rows, blocks, bodies);
  // bitwise, so that -0 and 0 differ as the arithmetic may
  if (!key_.empty() && key_.size() == key_next_.size() &&
      std::memcmp(key_.data(), key_next_.data(), key_.size() * sizeof(double)) == 0) {
    return true;
  }
  key_.clear();
  rows_ = &rows;
  blocks_ = &blocks;
  row_count_ = static_cast<int>(rows.size());
  if (!Build(bodies)) return false;
  for (int i = 0; i < count_; ++i) Diagonal(nodes_[i], bodies, &nodes_[i].D_matrix);
  // children before parents: D_p -= H(i,p)^T D_i^-1 H(i,p)
  NodeMatrix coupling;
  for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
    Node& n = nodes_[*it];
    n.D.compute(n.D_matrix);
    if (n.parent < 0) continue;
    Node& p = nodes_[n.parent];
    if (n.body >= 0) {
      Coupling(p, n, &coupling);
      n.H_parent = coupling.transpose();
    } else {
      Coupling(n, p, &n.H_parent);
    }
    n.J = n.D.solve(n.H_parent);
    p.D_matrix.noalias() -= n.H_parent.transpose() * n.J;
  }
  rows_ = nullptr;  // read while factoring only
  blocks_ = nullptr;
  key_.swap(key_next_);
  return true;
}

void JointTreeFactor::Solve(const std::vector<JointBlock>& blocks, const Eigen::VectorXd& b,
                            Eigen::VectorXd* lambda) {
  for (int i = 0; i < count_; ++i) {
    Node& n = nodes_[i];
    n.x.setZero(n.dim);
    int r = n.body >= 0 ? 6 : 0;
    for (int k : n.blocks) {
      n.x.segment(r, blocks[k].count) = b.segment(blocks[k].first, blocks[k].count);
      r += blocks[k].count;
    }
  }
  // forward (children first), diagonal, backward (parents first)
  for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
    const Node& n = nodes_[*it];
    if (n.parent >= 0) nodes_[n.parent].x.noalias() -= n.J.transpose() * n.x;
  }
  for (int i = 0; i < count_; ++i) nodes_[i].x = nodes_[i].D.solve(nodes_[i].x);
  for (int i : preorder_) {
    Node& n = nodes_[i];
    if (n.parent >= 0) n.x.noalias() -= n.J * nodes_[n.parent].x;
  }
  lambda->setZero(row_count_);
  for (int i = 0; i < count_; ++i) {
    const Node& n = nodes_[i];
    int r = n.body >= 0 ? 6 : 0;
    for (int k : n.blocks) {
      lambda->segment(blocks[k].first, blocks[k].count) = -n.x.segment(r, blocks[k].count);
      r += blocks[k].count;
    }
  }
}

bool JointGraphIsTree(const std::vector<JointBlock>& blocks, const std::vector<SolverBody>& bodies) {
  UnionFind sets(static_cast<int>(bodies.size()));
  for (const JointBlock& blk : blocks) {
    if (Dynamic(blk.a, bodies) && Dynamic(blk.b, bodies) && !sets.Join(blk.a, blk.b)) return false;
  }
  return true;
}

bool SolveJointsTree(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                     const std::vector<SolverBody>& bodies, const Eigen::VectorXd& b, Eigen::VectorXd* lambda) {
  // one per thread, kept so that its nodes' storage is reused by the next
  // system instead of allocated again; nothing of one system reaches the next
  thread_local JointTreeFactor factor;
  if (!factor.Factor(rows, blocks, bodies)) return false;
  factor.Solve(blocks, b, lambda);
  return true;
}

}  // namespace contactsim
