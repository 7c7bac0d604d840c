// Contact constraints of extended position based dynamics (Mueller et al.
// 2020, "Detailed rigid body simulation with extended position based
// dynamics", sec. 3.5-3.6), found once per step and carried through the
// sub-steps by their anchors (Macklin et al. 2019, "Small steps in physics
// simulation"; the relative anchors of Catto's soft step, 2024).
//
// A detected contact is remembered by each body's anchor in the body's own
// frame and its world normal n (from A to B, held for the step). The anchor
// is the surface point moved inward by the shape's radius (a sphere's is its
// centre, a capsule's a point of its segment), so a rolling ball keeps
// touching the ground however far it turns within the step. The separation
// at the current poses is
//   s = n . (c_B - c_A) - rho_A - rho_B,   c_i = x_i + R_i a_i,
// with a_i the anchors and rho_i the radii; s < 0 is a penetration.
//
// In a sub-step's position solve (after the prediction):
//   * non-penetration: d = -s, dlambda = (d - alpha~ lambda) / (w + alpha~),
//     lambda >= 0 accumulated over the sub-step (a point that pushed and has
//     come apart takes its push back); d at most max_push_velocity h, so an
//     overlap the step's contacts did not foresee (a tumbling box's corner
//     that turned down within the step) is removed over several sub-steps
//     rather than flung apart at once. With alpha = 0 the points of a body
//     pair that share n are solved as one block (normal_block.h: K^-1, or
//     K^+ for a face's four corners, so a level face gets four equal pushes
//     whatever order its corners come in); a block whose solution would
//     pull is swept point by point;
//   * static friction (eq. 26-27): the patch of the pair's points holds its
//     tangential offset (xpbd_patch_friction.h), solved with the points
//     that push held where they are (xpbd_held_friction.h).
// The velocity pass (restitution, dynamic friction) is xpbd_velocity_pass.h.
// Effective masses and the blocks' K use the lever arms and inverse
// inertias of the step's start (first order in the step's turn).
#pragma once

#include <algorithm>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/block_colours.h"
#include "service/contact/normal_block.h"
#include "service/contact/soft/soft_bodies.h"
#include "service/contact/xpbd/xpbd_articulation.h"
#include "service/physics/world.h"

namespace contactsim {

struct XpbdPoint {
  int a = -1, b = -1;             // body indices
  Vec3 anchor_a, anchor_b;        // m, each body's anchor in its own frame
  double radius_a = 0.0, radius_b = 0.0;  // m, the shapes' rounding
  Vec3 n;                         // unit, world, from A to B
  Vec3 ra;                        // m, contact point minus A's centre, step start
  Vec3 ra_n, rb_n, ia_n, ib_n;    // r x n and I^-1 (r x n), step start
  double w_n = 0.0;               // 1/kg, K along n
  // n . (the linear responses of A and B to the row): 1/m_A + 1/m_B for free
  // bodies; K_ij = k_lin_j + (r_Ai x n) . ia_n_j + (r_Bi x n) . ib_n_j
  double k_lin = 0.0;
  // a body of the pair is held by rigid joints: its pushes go through
  // XpbdArticulation (ia_n, ib_n its angular responses then)
  bool jointed = false;
  double restitution = 0.0;
  // per sub-step
  double lambda_n = 0.0;          // kg m, accumulated normal multiplier
  // an overlap present at the step's start: tolerated, slack0 - slack_rate t
  // at the step's time t, while positive (AllowXpbdStartOverlaps)
  double slack0 = 0.0;            // m
  double slack_rate = 0.0;        // m/s
  // per step
  Vec3 impulse = Vec3::Zero();    // N s on B (world) over the step
};

// What the step's preparation of the friction patches needs of a point
// besides its rows, kept apart so that the sub-steps sweep only the rows.
struct XpbdPointFrame {
  Vec3 rb;                        // m, contact point minus B's centre, step start
  Vec3 material_a, material_b;    // m, the surface points in the bodies' frames
  double friction = 0.0;
};

// A body's pose and velocities after a sub-step's prediction (the velocity
// pass's v~, read only at the points that pushed).
struct XpbdPose {
  Vec3 x;
  Quat q;
  Vec3 v, w;
};

// The points of `contacts` at the step's start: `blocks` groups each body
// pair's points, orders the blocks from the highest down (sweep_order.h)
// and then colour by colour (block_colours.h, `colours`; their K is
// inverted when a sub-step first needs it, XpbdSubsetInverse), and the
// points and their frames are stored in that order, so that the sub-steps
// read them front to back; point_of[k] is contact k's place. The blocks on
// bodies of a jointed component are solved serially (a push on one moves
// the others) and their points take the component's mobility
// (`articulation`).
void PrepareXpbdPoints(const ContactSet& contacts, const World& world, const std::vector<SoftBody>& bodies,
                       const XpbdArticulation& articulation, std::vector<XpbdPoint>* points, std::vector<XpbdPointFrame>* frames,
                       std::vector<NormalBlock>* blocks, BlockColours* colours, std::vector<int>* point_of);

// Overlaps present at the step's start (contact k's depth, point
// point_of[k], up to most[k]) are removed at `velocity` (m/s), or within
// `settle_time` (s) where that is faster: until then a point is held at its
// allowed overlap rather than at s = 0 (XpbdSlack), so such an overlap
// leaves in position at that speed, and the velocity pass keeps the push
// out of the velocity (Box2D's soft step likewise pushes overlaps out at a
// bounded speed and relaxes the push's velocity away, Catto 2024; PhysX's
// max depenetration velocity bounds it). An overlap the first sub-step (`h`,
// s) would remove at that rate is left to the sub-steps.
void AllowXpbdStartOverlaps(const ContactSet& contacts, const std::vector<int>& point_of,
                            const std::vector<double>& most, double velocity, double settle_time, double h,
                            std::vector<XpbdPoint>* points);

// The overlap point p is allowed at the step's time t (s; m).
inline double XpbdSlack(const XpbdPoint& p, double t) {
  return p.slack0 > 0.0 ? std::max(p.slack0 - p.slack_rate * t, 0.0) : 0.0;
}

// The point's separation at the world's current poses (m, < 0 penetrating)
// and, if asked, the surface points of A and B.
double XpbdSeparation(const XpbdPoint& p, const World& world, Vec3* pa = nullptr, Vec3* pb = nullptr);

// Zeroes the sub-step's multipliers of block m's points.
void BeginXpbdSubstep(const NormalBlock& m, std::vector<XpbdPoint>* points);

// The point's normal velocity v_n = n . (v_B - v_A) + (r_B x n) . w_B - (r_A x n) . w_A.
inline double XpbdNormalVelocity(const XpbdPoint& p, const Vec3& va, const Vec3& wa, const Vec3& vb, const Vec3& wb) {
  return p.n.dot(vb - va) + p.rb_n.dot(wb) - p.ra_n.dot(wa);
}

// The inverses of a block's K met in this step (K is the step's start one,
// so an inverse holds for the whole step): the whole block's, and the last
// two subsets', by the subset's bit mask.
struct XpbdSubsetCache {
  int full = -1;  // the whole block: -1 not inverted yet, 0 no block applies, 1 in full_inv
  Eigen::Matrix4d full_inv;
  int mask[2] = {-1, -1};
  bool ok[2] = {false, false};
  Eigen::Matrix4d inv[2];
  int next = 0;
};

// What a sub-step's position solve needs.
struct XpbdSolve {
  double h = 0.0;            // s, the sub-step
  double elapsed = 0.0;      // s, from the step's start to the sub-step's end
  double alpha_tilde = 0.0;  // 1/kg, compliance / h^2
  double max_push = 0.0;     // m, the deepest overlap one sub-step removes
  const XpbdArticulation* articulation = nullptr;  // the jointed points' pushes
};

// The non-penetration of one block's points (one position iteration).
void SolveXpbdBlockNormals(World& world, const std::vector<SoftBody>& bodies, const XpbdSolve& solve,
                           const NormalBlock& block, XpbdSubsetCache& cache, std::vector<XpbdPoint>& points);

// K^-1 of the block's points idx[0..n) (in block order; K^+ for a face's
// four), 1 / K for one point, in the top left of the matrix pointed to (the
// cache's own, not copied); null when no block applies (three points on a
// line). XpbdSubsetInverse answers the common case, the whole block already
// inverted, inline, and asks XpbdSubsetInverseFind otherwise.
const Eigen::Matrix4d* XpbdSubsetInverseFind(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies,
                                             const NormalBlock& block, const int* idx, int n, XpbdSubsetCache& cache);
inline const Eigen::Matrix4d* XpbdSubsetInverse(const std::vector<XpbdPoint>& points,
                                                const std::vector<SoftBody>& bodies, const NormalBlock& block,
                                                const int* idx, int n, XpbdSubsetCache& cache) {
  if (n == block.count && cache.full == 1) return &cache.full_inv;
  return XpbdSubsetInverseFind(points, bodies, block, idx, n, cache);
}

// A jointed block's K at its bodies' present mobility (after
// XpbdArticulation::Refresh): its points' responses again, and the
// inverses of its K forgotten.
void RefreshJointedXpbdBlock(const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
                             const NormalBlock& m, XpbdSubsetCache* cache, std::vector<XpbdPoint>* points);

// Moves a dynamic body by dx and turns it by the small rotation vector theta
// (first order, renormalised; a turn below 1e-18 rad, round-off, is left
// out); others stay.
void DisplaceXpbdBody(RigidBody& body, const SoftBody& s, const Vec3& dx, const Vec3& theta);

}  // namespace contactsim
