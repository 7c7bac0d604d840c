// Contacts on jointed bodies in xpbd: a contact push on a body held by rigid
// joints moves the body's jointed component as its joints let it
// (joint_mobility.h), both in the position solve (the points' pushes and
// the patches' static friction) and in the velocity pass (restitution and
// the friction brake), and the pair's effective mass is taken with the
// body's constrained mobility Z_ii instead of its free inverse mass and
// inertia.
//
// Why: a sub-step solves the joints, then the contacts, then projects the
// joints (xpbd_method.h, 2b). Pushed as a free body, a light plank under a
// load takes most of each contact push, the joints' projection takes it
// back, and the load is held by what is left: a 0.1 kg box slid 23 m off a
// 0.5 kg plank welded at 34 degrees with mu = 0.9 (tan 34 = 0.66), and the
// velocity pass left the welded plank moving (1e-3 rad/s) every sub-step.
// Through Z the weld is a static support, a hinge one that turns about its
// axis, and what joints and contacts ask of a body is met together to
// first order (the joints' projection then removes a second-order rest).
//
// Left free (the joints' projection after the sweep as before): a contact
// between two bodies of one jointed component (a chain folding onto itself,
// whose joint and contact rows can ask for motions no displacement meets),
// and every body when the joints are compliant (joint_compliance > 0,
// joints solved in the sweep).
#pragma once

#include <vector>

#include "service/contact/joints/joint_mobility.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/physics/world.h"

namespace contactsim {

class XpbdArticulation {
 public:
  // The responses of the jointed bodies among `touching` (per world body:
  // it has a contact this step) at the present poses, with the inverse
  // masses and inertias of `bodies`; nothing when `rigid_joints` is false.
  void Prepare(const World& world, const std::vector<SoftBody>& bodies, const std::vector<char>& touching,
               bool rigid_joints);
  // The same responses again at the present poses (each sub-step, after the
  // prediction). Z depends on the pose: taken once a step, a swing's
  // support moved along the tangent of its path at the step's start, its
  // load's weight decelerated it too little on the way up and sped it up
  // too much on the way down (explicit in the geometry), and a swing with
  // 50 kg on it gained 7% of its energy in 3 s (3.9 J, half that at half
  // the step). Taken after each prediction, the joints' geometry is that of
  // the sub-step's end, as the joints' projection has it.
  void Refresh(const World& world, const std::vector<SoftBody>& bodies);
  bool active() const { return active_; }
  // Whether a contact between bodies a and b takes the jointed path.
  bool Applies(int a, int b) const {
    return active() && (mobility_.Jointed(a) || mobility_.Jointed(b)) && !mobility_.SameComponent(a, b);
  }
  // Whether body i belongs to a jointed component (its contacts are solved
  // serially: a push on one body moves the others, block_colours.h).
  bool InComponent(int i) const { return active() && mobility_.InComponent(i); }
  // Whether body i's contacts take its component's mobility.
  bool Jointed(int i) const { return active() && mobility_.Jointed(i); }
  // Body i's velocity (v; w) when the velocities `v` and `w` of its
  // component's bodies are projected onto its joints, P = Z M (the
  // M-orthogonal projection onto J v = 0; Z symmetric, so body i's row of
  // Z is the transpose of its responses): what the joints leave of a
  // predicted velocity. A welded plank's gravity kick, which the joints
  // take back, then does not read as the plank falling away from its load.
  // Jointed(i) only.
  template <class Pose>
  Vec6 Projected(int i, const std::vector<Pose>& poses, const std::vector<SoftBody>& bodies) const {
    Vec6 out = Vec6::Zero();
    for (const JointMobility::Response* r = mobility_.begin(i); r != mobility_.end(i); ++r) {
      const SoftBody& s = bodies[r->body];
      Vec6 momentum;
      momentum << poses[r->body].v / s.inv_mass, s.inv_inertia.inverse() * poses[r->body].w;
      out += r->z.transpose() * momentum;
    }
    return out;
  }
  // Body i's motion under the wrench (lin; ang): Z_ii (lin; ang) when
  // jointed, M^-1 (lin; ang) otherwise.
  Vec6 Response(int i, const SoftBody& s, const Vec3& lin, const Vec3& ang) const;
  // Body k's motion under the wrench w on body i: Z_ki w when i is
  // jointed (0 for k outside i's component), M^-1 w for k = i otherwise,
  // else 0.
  Vec6 ResponseOf(int k, int i, const SoftBody& s, const Vec6& w) const;
  // Moves (positions) or kicks (velocities) body i's component by the
  // response to the wrench (force at the centre of mass, torque) on body i.
  void Displace(World& world, const std::vector<SoftBody>& bodies, int i, const Vec3& force,
                const Vec3& torque) const;
  void Kick(std::vector<SoftBody>& bodies, int i, const Vec3& force, const Vec3& torque) const;

 private:
  void Build(const World& world, const std::vector<SoftBody>& bodies);

  JointMobility mobility_;
  std::vector<SolverBody> solver_;
  std::vector<char> touching_;
  bool active_ = false;
};

}  // namespace contactsim
