// The contact points of one body pair with one normal solved as a block:
// the normal rows of a manifold are coupled through the bodies' rotations,
// so one Gauss-Seidel sweep over them gives the first point swept more than
// its share. The block solves them together (Catto's block solver for two
// points, Box2D):
//   K = J M^-1 J^T of the manifold's normal rows (fixed for the step, as the
//       anchors are), dv = K^-1 (v_n + bias),
//   lambda_i += -mass_scale_i dv_i - impulse_scale_i lambda_i,
// accepted when every lambda_i stays >= 0; otherwise (a point lifting off)
// the points are swept one by one. Friction stays per point.
// Two points (an edge, a lying capsule) and three get K^-1. Four points of a
// face act on three velocities (v_n and two tilts), so their K is singular:
// they get its pseudo-inverse, the least-norm increment, which keeps a
// symmetric face's impulses symmetric whatever order its points come in
// (docs/physics.md, "soft").
#pragma once

#include <Eigen/Core>
#include <vector>

#include "service/contact/soft/soft_contact.h"

namespace contactsim {

struct SoftManifold {
  int first = 0;          // points [first, first + count)
  int count = 0;
  bool block = false;     // two to four points with one normal and K (pseudo-)inverted
  Eigen::Matrix4d inv_k = Eigen::Matrix4d::Zero();
};

// Groups consecutive points of one body pair (the narrowphase emits a
// pair's points together) and inverts K where a block solve applies.
void BuildSoftManifolds(const std::vector<SoftPoint>& points, std::vector<SoftManifold>* manifolds);

// One pass over every manifold: each point's friction, then the normal rows.
void SolveSoftManifolds(const SoftPass& pass, const std::vector<SoftManifold>& manifolds,
                        std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies);

}  // namespace contactsim
