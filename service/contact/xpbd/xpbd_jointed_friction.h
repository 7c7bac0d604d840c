// Static friction of the patches on jointed bodies in xpbd, solved together
// (docs/physics.md, "Jointed supports").
//
// Each patch's static friction is one small solve through the jointed
// body's constrained mobility (xpbd_patch_friction.h, XpbdArticulation), and
// the sweep takes the patches one after another. Several patches on one
// light jointed support share its motion: each patch's solve moves the
// support, which opens the patches solved before it, and the sweep meets
// the support's share at about 1 - m_support / m_load a sweep (five boxes
// of 10 kg on a 0.5 kg hinged plank crept 10.9 mm in 3 s). So after each
// sweep the jointed patches that stick or are held at their cone are
// solved at once:
//   K dlambda = e,  K_pq = J_p Z J_q^T,
// e the offsets their static friction would undo (XpbdPatchError), J_p a
// patch's rows (t1, t2 at its centre, the twist about n) and Z the bodies'
// responses (XpbdArticulation::ResponseOf: the joints' constrained mobility
// within a jointed component, M^-1 for a free body). A patch the answer
// takes past its cone (mu sum lambda_n, its twist within that times its
// radius) keeps what the sweep gave it and the rest are solved again.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/xpbd/xpbd_articulation.h"
#include "service/contact/xpbd/xpbd_patch_friction.h"

namespace contactsim {

class XpbdJointedFriction {
 public:
  // Most patches solved together; more keep the sweep's answer (a dense
  // solve of three rows a patch).
  static constexpr int kMaxPatches = 32;

  // The patches among `jointed_blocks` (patch indices) that stick or are
  // held at their cone (XpbdPatch::clamped) solved
  // together at the world's present poses; their multipliers and bodies
  // move by the answer.
  void Solve(World& world, const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
             const std::vector<int>& jointed_blocks, const std::vector<XpbdPoint>& points,
             std::vector<XpbdPatch>& patches);

 private:
  // One row of a member patch: its Jacobian on A (negated) and on B.
  struct Row {
    int patch = 0;  // index in patches
    int axis = 0;   // 0, 1: t1, t2; 2: twist
    Vec6 ja = Vec6::Zero(), jb = Vec6::Zero();
  };
  void BuildRows(const std::vector<XpbdPoint>& points, const std::vector<XpbdPatch>& patches);
  // K over rows_ (XpbdArticulation::ResponseOf).
  void BuildK(const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
              const std::vector<XpbdPoint>& points, const std::vector<XpbdPatch>& patches);

  std::vector<int> members_;  // patch indices
  std::vector<Row> rows_;
  Eigen::MatrixXd k_;
};

}  // namespace contactsim
