// Static friction of xpbd (Mueller et al. 2020, eq. 26-27) on a body pair's
// contact patch as a whole: the patch's points (a face's corners, an edge's
// two ends, one point) hold their tangential offsets through one rigid
// constraint at their centre, two tangent rows and, for two or more points,
// a twist row about n:
//   u = mean of the points' slips,  theta = sum n . (d_i x s_i) / sum |d_i|^2,
// with s_i the tangential offset of point i's surface points (material
// points, turning with their bodies) since the contact was found and d_i the
// point's place from the centre. One solve of the 3 x 3 K (fixed for the
// step) undoes both, so a face's corners share the friction whatever their
// order: one corner after another, the first took the whole slip and left
// its cone, and a sliding box on a slope crept; corners sharing a Jacobi
// update under-corrected and crept too.
// The slip is measured since the step's start rather than over the
// sub-step, so what one sub-step leaves is corrected in the next, and what
// the step's last sub-step leaves is carried into the next step
// (XpbdPatchSlip). The cone:
// |lambda_t| <= mu sum lambda_n and |lambda_twist| <= mu sum lambda_n r, r
// the points' mean distance from the centre; beyond it the patch slides (the
// velocity pass brakes it) and holds its new offset from then on.
// The cone over the step: a patch of free bodies holds the sum of its
// friction over the step's sub-steps so far within mu times the sum of its
// pushes over them (Coulomb's law on the step's impulses, as the
// velocity-level methods hold it), not each sub-step's alone. A box that
// rocks on its downhill edge after landing on a slope shares its load
// among its corners differently from one sub-step to the next (0.84, 1.00,
// 1.20 m g cos h^2 in a cycle), and the weakest sub-step alone let the
// patch go every few sub-steps: 6.7 mm in 3 s on 38 degrees at mu 0.9.
// A sub-step that slides or stops touching starts the sums again.
// A jointed patch (XpbdArticulation) keeps its offset instead and takes the
// cone's most, mu sum lambda_n, along its correction, and the velocity
// pass's brake keeps the sum of that and its own impulses within the same
// limit. On a light jointed support the sweep shares the support's motion
// among its patches one after another, and a patch's share passes the cone
// on the way to the answer: let go, 50 kg of boxes slid off a 0.5 kg swing
// and the loads on a welded plank let go every third sub-step (6.7 mm in
// 3 s); held at the cone, 0.30 and 0.13 mm (the 0.1 mm fall onto the
// plank included).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "service/contact/normal_block.h"
#include "service/contact/patch_torsion.h"
#include "service/contact/xpbd/xpbd_contact.h"
#include "service/contact/xpbd/xpbd_held_friction.h"

namespace contactsim {

struct XpbdPatch {
  // What the velocity pass's brake reads, together at the front (it runs
  // twice a block a sub-step, and the patch's other fields stayed out of
  // the cache lines it needs):
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();  // unit, (t1, t2, n) right-handed for the first point's n
  Vec3 ra = Vec3::Zero(), rb = Vec3::Zero();  // m, the patch centre minus each body's centre, step start
  Eigen::Matrix3d inv_k = Eigen::Matrix3d::Zero();  // rows t1, t2, twist
  double friction = 0.0;
  double twist_radius = 0.0;           // m, the points' mean distance from the centre (or r_eff); 0: no twist row
  double lever_scale = 1.0;            // the points' friction acts at lever_scale d_i (patch_torsion.h)
  bool valid = false;
  bool jointed = false;                // its pushes go through XpbdArticulation (XpbdPoint::jointed)
  bool compound = false;               // a body of the pair is a compound (BrakeXpbdPatch)
  int first = 0, count = 0;            // the points [first, first + count)
  double spread = 0.0;                 // m^2, sum of the points' squared distances from the centre
  // The offset is linear in the points' material points m_i, so the patch
  // keeps their sums (below) and turns two tangents per body a sub-step
  // instead of reading every point (PatchOffset):
  Vec3 mean_a = Vec3::Zero(), mean_b = Vec3::Zero();  // m, mean m_i in A's and B's frames
  // sum_i d_i[k] m_i / spread for k = t1, t2, d_i the point's place from the centre
  Vec3 twist_a[2] = {Vec3::Zero(), Vec3::Zero()}, twist_b[2] = {Vec3::Zero(), Vec3::Zero()};
  double twist_c[2] = {0.0, 0.0};      // sum_i d_i[k] / spread (0 up to round-off)
  // per step: the offsets static friction holds
  Vec3 origin = Vec3::Zero();          // (m, m, rad) along t1, t2 and the twist
  // A patch that does not touch holds its offset at the present poses; they
  // are kept instead, and the offset (the same number) is found only when a
  // later sub-step touches: most untouched patches never need it.
  bool origin_pending = false;
  bool sticking = false;               // static friction held it at its last solve
  bool clamped = false;                // a jointed patch held at its cone in this sub-step
  Vec3 hold_xa = Vec3::Zero(), hold_xb = Vec3::Zero();
  Quat hold_qa = Quat::Identity(), hold_qb = Quat::Identity();
  // per sub-step
  Vec3 lambda_t = Vec3::Zero();        // kg m
  double lambda_twist = 0.0;           // kg m^2
  double pushed = 0.0;                 // kg m, the points' sum of lambda_n its friction solve held
  // per step: the friction and pushes of the step's earlier sub-steps that
  // held (since it last slid or let go), which the cone bounds together
  // with the sub-step's own (the cone over the step, above)
  Vec3 step_lambda_t = Vec3::Zero();   // kg m
  double step_pushed = 0.0;            // kg m
  // per step: K of the rows (t1, t2, twist) alone, and with the pushing
  // points held (xpbd_held_friction.h), built when a sub-step first needs it
  Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
  XpbdHeldRows held;
};

// One patch per normal block, with its K inverted; `frames` is parallel to
// `points`. With `torsion` uniform, a patch of three or more points
// twists against mu sum lambda_n r_eff, r_eff its area's mean distance from
// its centroid (patch_torsion.h), instead of its points' mean distance.
// K of a jointed patch takes its bodies' mobility from `articulation`.
void PrepareXpbdPatches(const std::vector<NormalBlock>& blocks, const std::vector<XpbdPoint>& points,
                        const std::vector<XpbdPointFrame>& frames, const std::vector<SoftBody>& bodies,
                        const XpbdArticulation& articulation, PatchTorsion torsion,
                        std::vector<XpbdPatch>* patches);

// A jointed patch's K inverted again at its bodies' present mobility.
void RefreshJointedXpbdPatch(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies,
                             const XpbdArticulation& articulation, XpbdPatch* patch);

// What a patch's static friction left uncorrected at a step's end: the
// slip of A's surface against B's in the contact plane (m, world) and its
// twist about n (rad). Dropped at the step's end, it came back as creep:
// each step's sweeps leave a little, and a bridge of boxes walked
// 0.2-0.3 mm in 10 s at 12 sub-steps. Carried into the next step as the
// offset to undo, static friction holds across steps as within one.
struct XpbdPatchSlip {
  Vec3 along = Vec3::Zero();
  double twist = 0.0;
};

// The patch's slip now, false when static friction held nothing at its
// last solve (invalid, not touching, or sliding: then there is no slip to
// keep).
bool XpbdPatchSlipNow(const World& world, const XpbdPatch& patch, const std::vector<XpbdPoint>& points,
                      XpbdPatchSlip* slip);

// Starts the patch's static friction from a slip carried over from the last
// step: it holds the offset that undoes it, in this step's tangent frame.
void CarryXpbdPatchSlip(const XpbdPatchSlip& slip, XpbdPatch* patch);

// What the patch's static friction would undo now: its offset at the
// world's present poses less the offset it holds (t1, t2, twist; m, m, rad).
// Only for a patch whose origin is known (not origin_pending).
Vec3 XpbdPatchError(const World& world, const XpbdPatch& patch, const std::vector<XpbdPoint>& points);

// Zeroes the patch's multipliers of the sub-step, after adding the last
// sub-step's to the step's sums where it held (the cone over the step).
void BeginXpbdPatch(XpbdPatch* patch);

// The patch's static friction at the world's current poses (after its
// points' non-penetration, block `block` with its inverses in `cache`),
// accumulated in lambda_t and lambda_twist (the velocity pass reports
// lambda_t / h). A patch of free bodies is solved with its pushing points
// held (xpbd_held_friction.h), whose pushes then change too.
void SolveXpbdPatchFriction(World& world, const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
                            const NormalBlock& block, XpbdSubsetCache& cache, XpbdPatch& patch,
                            std::vector<XpbdPoint>& points);

// Dynamic friction of the patch in the velocity pass (eq. 30, on the patch
// as a whole): the impulse and twist that stop its relative motion at the
// centre, when the impulse is within mu pushed / h (Coulomb's disk,
// `pushed` the sum of the points' lambda_n, > 0) and the twist within that
// times the patch's radius. Beyond either the patch slides, and gets what
// its points' Coulomb disks give for its slip and spin, each point's
// friction mu lambda_n / h against its own slip v + spin n x d_i (summed to
// a force and a twist about the centre), no more in either than stopping
// would take: with the two limits apart, a 0.2 m cube sliding at 2 m/s and
// spinning at 10 rad/s had its spin braked by the whole mu N r and stopped
// spinning in 0.10 s, where its points' friction takes 0.44 s
// (docs/physics.md, "Friction against spin"). A point alone (no twist row) keeps the disk.
// One impulse for the patch keeps a sliding face's corners alike:
// braked corner by corner, a box sliding down a slope picked up
// 0.008-0.014 rad/s of spin. `spent` holds what the patch's earlier brakes of
// this pass applied (t1, t2, twist): the limits bound their sum, as
// accumulated impulses are clamped (Catto 2005). The impulse applied is
// added to `applied` (N s, world, on B), which the caller shares among the
// points for the report.
// A jointed patch's impulses go to the bodies' components (`articulation`,
// `bodies` holding A and B).
void BrakeXpbdPatch(double h, double pushed, const XpbdPatch& patch, const std::vector<XpbdPoint>& points,
                    const Vec3& n, const XpbdArticulation& articulation, std::vector<SoftBody>& bodies, Vec3* spent,
                    Vec3* applied);

}  // namespace contactsim
