// The contact points of one body pair with one normal: each point's
// friction, then the normal rows as a block (normal_block.h: K^-1 for two
// or three points, K's pseudo-inverse for a face's four), accepted when
// every impulse stays >= 0; otherwise (a point lifting off) the points are
// swept one by one. Friction stays per point.
#pragma once

#include <vector>

#include "service/contact/normal_block.h"
#include "service/contact/soft/soft_contact.h"

namespace contactsim {

using SoftManifold = NormalBlock;

// Groups consecutive points of one body pair (the narrowphase emits a
// pair's points together) and, with `invert`, inverts K where a block
// solve applies (InvertSoftManifolds; the float path inverts its own in
// float, soft_wide_kernels.h).
void BuildSoftManifolds(const std::vector<SoftPoint>& points, ParallelRunner& runner,
                        std::vector<SoftManifold>* manifolds, bool invert = true);
// K^-1 of each manifold where a block solve applies (on the world's threads).
void InvertSoftManifolds(const std::vector<SoftPoint>& points, ParallelRunner& runner,
                         std::vector<SoftManifold>* manifolds);
// The same for one of them.
void InvertSoftManifold(const std::vector<SoftPoint>& points, SoftManifold* m);

// Passes over the manifolds [begin, end) (one colour of block_colours.h,
// or all of them in order):
// the solve: each point's friction, then the normal rows.
void SolveSoftManifolds(const SoftPass& pass, const std::vector<SoftManifold>& manifolds, int begin, int end,
                        std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies);

}  // namespace contactsim
