// Static friction of an xpbd patch solved together with its pushing points
// (docs/methods/xpbd.md, "Friction with the normals held").
//
// The patch's friction rows (t1, t2 at its centre, the twist about n;
// xpbd_patch_friction.h) act at the contact plane, off the bodies' centres
// of mass, so on their own they turn the bodies as well as move them: a box
// held on a slope is pitched by its friction, and the next sub-step's
// normal pushes turn it back, which moves the patch's centre again. One
// Gauss-Seidel pass of normals then friction a sub-step leaves the pushes
// in a cycle (0.84, 1.00, 1.20 m g cos(theta) h^2 on 34 degrees) whose
// weakest sub-step cannot hold the friction the slope needs, and the patch
// lets go every third sub-step (6.7 mm in 3 s at mu 0.9).
//
// Held, the pushing points keep their separations while the friction
// moves the bodies, their pushes changing by what that takes: with J_n the
// held points' normal rows and J_f the friction rows,
//   [K_nn K_nf] [dl_n]   [0]
//   [K_fn K_ff] [dl_f] = [r],   K = J M^-1 J^T,  r the patch's slip,
// so  S dl_f = r,  S = K_ff - K_fn K_nn^+ K_nf  (the friction rows' K with
// the normals held, a Schur complement),  dl_n = -K_nn^+ K_nf dl_f.
// K_nn^+ is the normal block's own (normal_block.h: K^+ for a face's four
// corners, whose dependency K_nf never excites: its columns lie in the
// range of J_n). This is the patch's one rigid solve of all six relative
// motions, the static answer the cone is then checked against: the
// friction is mu times the held pushes' new sum at most, and every held
// push stays >= 0 (a point whose push would pull is let go and the rest
// solved again; a free point the step would press into the other body
// joins, brought to touching: its row's right side is its depth, d_n in
// dl_n = K_nn^+ (d_n - K_nf dl_f)). With the cone checked over the step
// (xpbd_patch_friction.h), a cube set down 0.1 mm above a slope with mu 0.9
// moves 0.071 / 0.101 / 0.404 mm in 3 s at 34 / 38 / 40 degrees
// (docs/methods/xpbd.md, "Friction with the normals held").
// Patches on jointed bodies (XpbdArticulation) and a compound's child
// patches keep the friction rows alone (xpbd_patch_friction.h).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/normal_block.h"
#include "service/contact/xpbd/xpbd_contact.h"

namespace contactsim {

// S and K_nn^+ K_nf of one set of held points, for the step (K is the step
// start's).
struct XpbdHeldRows {
  int mask = 0;  // the held points, bit i for the block's point i; 0: none built
  bool ok = false;
  bool ok_tangent = false;                       // s2_inv holds
  Eigen::Matrix4d inv_nn;                        // K_nn^+ of the held points (in mask order)
  Eigen::Matrix<double, kMaxNormalBlock, 3> g;   // K_nn^+ K_nf: the held pushes per unit friction
  Eigen::Matrix3d s_inv;                         // S^-1 over t1, t2, twist
  Eigen::Matrix2d s2_inv;                        // S^-1 over t1, t2 alone (the twist let go)
};

// The friction rows of a patch: t1 and t2 at its centre (lever arms ra,
// rb) and the twist about n, and their K without the normals (K_ff).
struct XpbdFrictionRows {
  Vec3 t1, t2, n;
  Vec3 ra, rb;
  const Eigen::Matrix3d* k_ff = nullptr;
  bool twist = false;  // the twist row is in (a patch of two or more points)
};

// Builds `held` for the block's points idx[0..count) (K_nn^+ from the
// block's cache, XpbdSubsetInverse). False (and held->ok false) when no
// block applies to them or S is singular.
bool BuildXpbdHeldRows(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies,
                       const NormalBlock& block, XpbdSubsetCache& cache, const XpbdFrictionRows& rows,
                       const int* idx, int count, XpbdHeldRows* held);

struct XpbdPatch;

// The static friction of a patch of free (not jointed) bodies with its
// pushing points held, at the world's present poses: `slip` is what it
// would undo (t1, t2, twist), `offset` its offset now and `pushed` the sum
// of its points' lambda_n (> 0). Sticking, the bodies move by dl_f and the
// held pushes dl_n, which join the points' lambda_n; past the cone it
// slides and holds its present offset from then on (as
// SolveXpbdPatchFriction); a twist past its limit is let go and the
// tangent rows solved without it (S over t1, t2). False when no held set
// applies (no inverse for its points, S singular): the caller then solves
// the friction rows alone.
bool SolveHeldXpbdPatchFriction(World& world, const std::vector<SoftBody>& bodies, const NormalBlock& block,
                                XpbdSubsetCache& cache, const Vec3& slip, const Vec3& offset, double pushed,
                                XpbdPatch& patch, std::vector<XpbdPoint>& points);

}  // namespace contactsim
