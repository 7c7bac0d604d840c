// The inverse of a symmetric positive definite matrix of at most 4 x 4 by
// Cholesky, K = L L^T and K^-1 = L^-T L^-1, written out on plain arrays.
//
// It makes the same operations in the same order as Eigen 3.4's
// LLT<Matrix4d> (LLT.h, the unblocked factor) and its solve for the
// identity (TriangularSolverMatrix.h, the small-panel kernel: multiplying
// by the pivots' reciprocals, the forward solve subtracting term by term,
// the backward one subtracting the sum), which the normal blocks used to
// call, so every block's K^-1 is the same bit for bit
// (tests/contact/small_spd_inverse_test.cpp checks it against Eigen): Eigen
// goes through its general blocked triangular solve for a 4 x 4, about
// 2,700 instructions a block, 1.6M of a box_pyramid step under lcp
// (BENCHMARKS.md, "### lcp").
#pragma once

#include <Eigen/Core>

namespace contactsim {

// The inverse of the top-left n x n of k (2 <= n <= 4; its lower triangle
// is read, nothing else) into the top-left of *inv, the rest of *inv left
// as it is, and L's diagonal into pivots[0, n). As if k were padded to
// 4 x 4 with the identity, which changes none of these bits. False when a
// pivot is not positive (or NaN): k is not positive definite.
bool SmallSpdInverse(const Eigen::Matrix4d& k, int n, Eigen::Matrix4d* inv, double* pivots);

}  // namespace contactsim
