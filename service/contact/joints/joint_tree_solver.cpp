#include "service/contact/joints/joint_tree_solver.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "service/contact/joints/small_lu.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

using Node = JointTreeFactor::Node;
constexpr int kMaxNodeRows = JointTreeFactor::kMaxNodeRows;

bool Dynamic(int index, const std::vector<SolverBody>& bodies) {
  return index >= 0 && bodies[index].inv_mass > 0.0;
}

// J of `row` on the side that is `body`, as (lin, ang)
void RowOn(const ConstraintRow& row, int body, double* j) {
  const bool a = row.a == body;
  std::copy_n((a ? row.lin_a : row.lin_b).data(), 3, j);
  std::copy_n((a ? row.ang_a : row.ang_b).data(), 3, j + 3);
}

// y -= A^T x, A rows x cols (row stride cols)
template <typename Cols>
void SubtractTransposedProduct(int rows, Cols col_count, const double* A, const double* x, double* y) {
  const int cols = col_count;
  for (int k = 0; k < rows; ++k) {
#pragma GCC unroll 8
    for (int c = 0; c < cols; ++c) y[c] -= A[k * cols + c] * x[k];
  }
}

// y -= A x, A rows x cols (row stride cols)
template <typename Cols>
void SubtractProduct(int rows, Cols col_count, const double* A, const double* x, double* y) {
  const int cols = col_count;
  for (int k = 0; k < rows; ++k) {
    double s = 0.0;
#pragma GCC unroll 8
    for (int c = 0; c < cols; ++c) s += A[k * cols + c] * x[c];
    y[k] -= s;
  }
}

// D (stride d) -= J^T H = H^T D_i^-1 H over H's first `rows` rows and
// `cols` columns (H and J: row stride cols)
template <typename Rows, typename Cols>
void SubtractProductOfTransposed(Rows row_count, Cols col_count, const double* H, const double* J, double* D, int d) {
  const int rows = row_count, cols = col_count;
  for (int r = 0; r < cols; ++r) {
    for (int c = 0; c < cols; ++c) {
      double s = 0.0;
#pragma GCC unroll 8
      for (int k = 0; k < rows; ++k) s += J[k * cols + r] * H[k * cols + c];
      D[r * d + c] -= s;
    }
  }
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

// H_ii of a node, dim x dim: a body's M = diag(m 1, I_world) bordered by the
// rows of its world joints, and every row's -R on the diagonal
void JointTreeFactor::Diagonal(const std::vector<SolverBody>& bodies, Node* n) const {
  const std::vector<ConstraintRow>& rows = *rows_;
  const int dim = n->dim;
  double* H = n->D.data();
  std::fill_n(H, dim * dim, 0.0);
  int r = 0;
  if (n->body >= 0) {
    const SolverBody& s = bodies[n->body];
    const Mat3 inertia = s.inv_inertia.inverse();
    for (int i = 0; i < 3; ++i) {
      H[i * dim + i] = 1.0 / s.inv_mass;
      for (int j = 0; j < 3; ++j) H[(3 + i) * dim + 3 + j] = inertia(i, j);
    }
    r = 6;
  }
  for (int k : n->blocks) {
    const JointBlock& blk = (*blocks_)[k];
    for (int i = 0; i < blk.count; ++i, ++r) {
      const ConstraintRow& row = rows[blk.first + i];
      if (n->body >= 0) {
        double j[6];
        RowOn(row, n->body, j);
        for (int c = 0; c < 6; ++c) H[r * dim + c] = H[c * dim + r] = j[c];
      }
      H[r * dim + r] = -kJointRegularisation * row.Diagonal(bodies) - row.cfm;  // R: regularisation and compliance
    }
  }
}

// H(n, parent): a joint's rows on its body's velocity block, as the joint
// node's rows (n a joint) or columns (n a body)
void JointTreeFactor::Coupling(const Node& parent, Node* n) const {
  const bool joint = n->body < 0;
  const Node& joint_node = joint ? *n : parent;
  const int body = joint ? parent.body : n->body;
  const JointBlock& blk = (*blocks_)[joint_node.blocks[0]];
  n->lead_rows = joint ? n->dim : 6;
  n->lead_cols = joint ? 6 : parent.dim;
  const int cols = n->lead_cols;
  double* H = n->H.data();
  if (!joint) std::fill_n(H + 6 * cols, (n->dim - 6) * cols, 0.0);  // a body's world-joint rows
  for (int i = 0; i < blk.count; ++i) {
    double j[6];
    RowOn((*rows_)[blk.first + i], body, j);
    for (int c = 0; c < 6; ++c) (joint ? H[i * cols + c] : H[c * cols + i]) = j[c];
  }
}

// J = D_n^-1 H(n, p) and D_p -= H(n, p)^T J, on H's nonzero rows and columns
void JointTreeFactor::Eliminate(Node* n, Node* p) const {
  Coupling(*p, n);
  const int dim = n->dim, rows = n->lead_rows, cols = n->lead_cols, pdim = p->dim;
  std::copy_n(n->H.data(), dim * cols, n->J.data());
  LuSolve(dim, n->D.data(), n->pivots.data(), n->J.data(), cols);
  WithSize<5, 6, 7, 8>(rows, [&](auto r) {
    WithSize<5, 6, 7, 8>(cols, [&](auto c) {
      SubtractProductOfTransposed(r, c, n->H.data(), n->J.data(), p->D.data(), pdim);
    });
  });
}

// Indices are stored as doubles (exact below 2^53); a block stores its
// bodies' masses and inertias, so that the key needs no body list (a row
// whose bodies are not its block's stores its own).
void JointTreeFactor::Key(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                          const std::vector<SolverBody>& bodies) {
  constexpr size_t kPerBlock = 4 + 2 * 10, kPerRow = 3 + 12;
  key_next_.resize(1 + kPerBlock * blocks.size() + kPerRow * rows.size());
  double* k = key_next_.data();
  *k++ = static_cast<double>(bodies.size());
  auto put = [&k](const double* v, int n) { k = std::copy(v, v + n, k); };
  auto body = [&](int i) {
    if (i < 0) {
      k = std::fill_n(k, 10, 0.0);  // the world
      return;
    }
    *k++ = bodies[i].inv_mass;
    put(bodies[i].inv_inertia.data(), 9);
  };
  size_t strays = 0;  // rows whose bodies are not their block's
  for (const JointBlock& blk : blocks) {
    *k++ = blk.first;
    *k++ = blk.count;
    *k++ = blk.a;
    *k++ = blk.b;
    body(blk.a);
    body(blk.b);
    for (int r = blk.first; r < blk.first + blk.count; ++r) strays += rows[r].a != blk.a || rows[r].b != blk.b;
  }
  for (const ConstraintRow& row : rows) {
    k[0] = row.a;
    k[1] = row.b;
    k[2] = row.cfm;
    for (int i = 0; i < 3; ++i) {
      k[3 + i] = row.lin_a[i];
      k[6 + i] = row.ang_a[i];
      k[9 + i] = row.lin_b[i];
      k[12 + i] = row.ang_b[i];
    }
    k += kPerRow;
  }
  if (strays == 0) return;
  const size_t used = static_cast<size_t>(k - key_next_.data());
  key_next_.resize(used + 20 * strays);
  k = key_next_.data() + used;
  for (const JointBlock& blk : blocks) {
    for (int r = blk.first; r < blk.first + blk.count; ++r) {
      if (rows[r].a == blk.a && rows[r].b == blk.b) continue;
      body(rows[r].a);
      body(rows[r].b);
    }
  }
}

bool JointTreeFactor::Factor(const std::vector<ConstraintRow>& rows, const std::vector<JointBlock>& blocks,
                             const std::vector<SolverBody>& bodies, bool reuse) {
  if (reuse) Key(rows, blocks, bodies);
  // bitwise, so that -0 and 0 differ as the arithmetic may
  if (reuse && keyed_ && key_.size() == key_next_.size() &&
      std::memcmp(key_.data(), key_next_.data(), key_.size() * sizeof(double)) == 0) {
    return true;
  }
  keyed_ = false;
  rows_ = &rows;
  blocks_ = &blocks;
  row_count_ = static_cast<int>(rows.size());
  // the graph (nodes, their order) depends on the shape alone
  shape_next_.assign(1, static_cast<int>(bodies.size()));
  for (const JointBlock& blk : blocks) {
    shape_next_.insert(shape_next_.end(), {blk.count, blk.a, blk.b, Dynamic(blk.a, bodies), Dynamic(blk.b, bodies)});
  }
  if (shape_next_ != shape_) {
    shape_.swap(shape_next_);
    shape_ok_ = Build(bodies);
  }
  if (!shape_ok_) return false;
  for (int i = 0; i < count_; ++i) Diagonal(bodies, &nodes_[i]);
  // children before parents: D_p -= H(i,p)^T D_i^-1 H(i,p)
  for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
    Node& n = nodes_[*it];
    LuFactor(n.dim, n.D.data(), n.pivots.data());
    if (n.parent >= 0) Eliminate(&n, &nodes_[n.parent]);
  }
  rows_ = nullptr;  // read while factoring only
  blocks_ = nullptr;
  if (reuse) {
    key_.swap(key_next_);  // key_next_'s storage, the last key, is written over by the next
    keyed_ = true;
  }
  return true;
}

void JointTreeFactor::Solve(const std::vector<JointBlock>& blocks, const Eigen::VectorXd& b,
                            Eigen::VectorXd* lambda) {
  for (int i = 0; i < count_; ++i) {
    Node& n = nodes_[i];
    int r = 0;
    if (n.body >= 0) r = 6, std::fill_n(n.x.data(), 6, 0.0);
    for (int k : n.blocks) {
      std::copy_n(b.data() + blocks[k].first, blocks[k].count, n.x.data() + r);
      r += blocks[k].count;
    }
  }
  // forward (children first), diagonal, backward (parents first)
  for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
    const Node& n = nodes_[*it];
    if (n.parent < 0) continue;
    WithSize<5, 6, 7, 8>(n.lead_cols, [&](auto cols) {
      SubtractTransposedProduct(n.dim, cols, n.J.data(), n.x.data(), nodes_[n.parent].x.data());
    });
  }
  for (int i = 0; i < count_; ++i) {
    Node& n = nodes_[i];
    LuSolve(n.dim, n.D.data(), n.pivots.data(), n.x.data(), 1);
  }
  for (int i : preorder_) {
    Node& n = nodes_[i];
    if (n.parent < 0) continue;
    WithSize<5, 6, 7, 8>(n.lead_cols, [&](auto cols) {
      SubtractProduct(n.dim, cols, n.J.data(), nodes_[n.parent].x.data(), n.x.data());
    });
  }
  lambda->setZero(row_count_);
  for (int i = 0; i < count_; ++i) {
    const Node& n = nodes_[i];
    int r = n.body >= 0 ? 6 : 0;
    for (int k : n.blocks) {
      for (int q = 0; q < blocks[k].count; ++q) (*lambda)[blocks[k].first + q] = -n.x[r + q];
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
