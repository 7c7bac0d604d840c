// How jointed bodies move under a push when their joints hold: the
// constrained mobility
//   Z = M^-1 - M^-1 J^T (J M^-1 J^T + R)^-1 J M^-1
// of the joint rows J (joint_rows.h, at the present poses), the M-orthogonal
// projection of a free response M^-1 w onto the motions J dq = 0 (the
// Schur complement of the joint rows in the system of joints and one more
// row; Featherstone, "Rigid body dynamics algorithms", 2008, ch. 7 calls
// Z_ii the articulated-body inverse inertia of body i). A wrench w = (F, tau)
// on body i (F at its centre of mass) moves every body k of i's jointed
// component by Z_ki w, linear and angular parts stacked.
//
// For a solver that takes a jointed body's contacts one at a time against
// the body's free inverse mass, each contact push moves the body off its
// joints and the joint solve after it moves it back: the pair's effective
// mass is that of the free body, not the jointed one, and the load on a
// light hinged or welded plank is held by a fraction of the push it needs
// (a 0.1 kg box on a 0.5 kg welded plank slid 23 m in 3 s under xpbd).
// With Z the contact sees the support as its joints let it move: a welded
// plank as a static body, a hinged one as a body turning about its hinge.
//
// Cost: six solves of the joint system (joint_solver.h, O(n) for a tree of
// n joints) for each body asked for, and 36 numbers for each body of its
// component.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/joints/joint_solver.h"
#include "service/physics/world.h"

namespace contactsim {

using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

class JointMobility {
 public:
  // One body's motion (dx; dtheta) = z w under a wrench w on the pushed body.
  struct Response {
    int body = -1;  // world body index
    Mat6 z = Mat6::Zero();
  };

  // Builds the responses of the bodies marked in `wanted` (world body
  // indices) that are dynamic and jointed to something; `bodies` are the
  // world's solver bodies (LoadSolverBodies: inverse masses and world
  // inverse inertias).
  void Build(const World& world, const std::vector<SolverBody>& bodies, const std::vector<char>& wanted,
             JointSolverKind solver = JointSolverKind::kTree);
  bool empty() const { return first_.empty(); }
  // Whether body i's responses were built.
  bool Jointed(int i) const { return i >= 0 && i < static_cast<int>(first_.size()) && first_[i] >= 0; }
  // Whether body i is a dynamic body of a jointed component.
  bool InComponent(int i) const {
    return i >= 0 && i < static_cast<int>(component_.size()) && component_[i] >= 0;
  }
  // Whether bodies i and j are dynamic bodies of one jointed component.
  bool SameComponent(int i, int j) const;
  // Body i's own response Z_ii (Jointed(i) only).
  const Mat6& Own(int i) const { return responses_[first_[i]].z; }
  // The responses of i's component to a wrench on i, i's own first.
  const Response* begin(int i) const { return responses_.data() + first_[i]; }
  const Response* end(int i) const { return responses_.data() + first_[i] + count_[i]; }

 private:
  std::vector<int> first_, count_;  // per world body: its responses, or -1
  std::vector<int> component_;      // per world body: its jointed component's root, or -1
  std::vector<Response> responses_;
  std::vector<ConstraintRow> rows_;  // the joint rows, kept for their storage
  std::vector<JointBlock> blocks_;
  std::vector<SolverBody> held_;     // M^-1 J^T y of one column
};

}  // namespace contactsim
