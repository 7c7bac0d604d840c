#include "service/contact/joints/joint_mobility.h"

#include "service/contact/joints/joint_rows.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// J u of every row for the free response u = M^-1 e_c of body i to the unit
// wrench e_c (c < 3: a force along axis c, else a torque about axis c - 3).
Eigen::VectorXd RowsAlong(const std::vector<ConstraintRow>& rows, const SolverBody& body, int i, int c) {
  const Vec3 lin = c < 3 ? Vec3(body.inv_mass * Vec3::Unit(c)) : Vec3::Zero();
  const Vec3 ang = c < 3 ? Vec3::Zero() : Vec3(body.inv_inertia.col(c - 3));
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size()));
  for (size_t r = 0; r < rows.size(); ++r) {
    if (rows[r].a == i) b[r] += rows[r].lin_a.dot(lin) + rows[r].ang_a.dot(ang);
    if (rows[r].b == i) b[r] += rows[r].lin_b.dot(lin) + rows[r].ang_b.dot(ang);
  }
  return b;
}

}  // namespace

bool JointMobility::SameComponent(int i, int j) const {
  const int n = static_cast<int>(component_.size());
  return i >= 0 && j >= 0 && i < n && j < n && component_[i] >= 0 && component_[i] == component_[j];
}

void JointMobility::Build(const World& world, const std::vector<SolverBody>& bodies, const std::vector<char>& wanted,
                          JointSolverKind solver) {
  first_.clear();
  count_.clear();
  component_.clear();
  responses_.clear();
  rows_.clear();
  blocks_.clear();
  AppendJointRows(world, bodies, 0.0, JointRowMode::kPosition, &rows_, &blocks_);
  if (rows_.empty()) return;
  const int n = static_cast<int>(bodies.size());
  auto dynamic = [&bodies](int i) { return i >= 0 && bodies[i].inv_mass > 0.0; };
  UnionFind sets(n);
  for (const JointBlock& blk : blocks_) {
    if (dynamic(blk.a) && dynamic(blk.b)) sets.Join(blk.a, blk.b);
  }
  component_.assign(n, -1);
  for (const JointBlock& blk : blocks_) {
    for (int i : {blk.a, blk.b}) {
      if (dynamic(i)) component_[i] = sets.Root(i);
    }
  }
  first_.assign(n, -1);
  count_.assign(n, 0);
  held_ = bodies;  // their inverse masses and inertias; v and w zeroed per column
  for (int i = 0; i < n; ++i) {
    if (!wanted[i] || component_[i] < 0) continue;
    // i's component, i first
    first_[i] = static_cast<int>(responses_.size());
    responses_.push_back(Response{i, Mat6::Zero()});
    for (int k = 0; k < n; ++k) {
      if (k != i && component_[k] == component_[i]) responses_.push_back(Response{k, Mat6::Zero()});
    }
    count_[i] = static_cast<int>(responses_.size()) - first_[i];
    Response* out = responses_.data() + first_[i];
    for (int c = 0; c < 6; ++c) {
      const Eigen::VectorXd y = SolveJointSystem(rows_, blocks_, bodies, RowsAlong(rows_, bodies[i], i, c), solver);
      for (int m = 0; m < count_[i]; ++m) held_[out[m].body].v.setZero(), held_[out[m].body].w.setZero();
      for (size_t r = 0; r < rows_.size(); ++r) rows_[r].Apply(-y[static_cast<Eigen::Index>(r)], held_);
      for (int m = 0; m < count_[i]; ++m) out[m].z.col(c) << held_[out[m].body].v, held_[out[m].body].w;
      if (c < 3) {
        out[0].z(c, c) += bodies[i].inv_mass;
      } else {
        out[0].z.col(c).tail<3>() += bodies[i].inv_inertia.col(c - 3);
      }
    }
  }
}

}  // namespace contactsim
