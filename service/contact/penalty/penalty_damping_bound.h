// The bound on a body pair's dashpots taken together, for the explicit
// step (penalty_explicit.h, stage 2).
//
// Stage 2 integrates each point's dashpot c_i implicitly against its own
// point's inverse effective mass K_ii, c_i' = c_i / (1 + h n_b c_i K_ii),
// so that one point alone takes at most its own velocity in a sub-step.
// The p points of a pair act on the same bodies, and in a sub-step their
// dashpots take the share b of a mode u of the pair's velocities
//   b(u) = h sum_i c_i' (J_i u)^2 / u^T M u,
// whose largest value over u is the largest eigenvalue of the p x p matrix
//   B = h W^1/2 K W^1/2,  W = diag(c_i'),  K_ij = J_i M^-1 J_j^T.
// Symplectic Euler is stable on a mode only while b <= 2 - (omega h)^2 / 2.
// Each c_i' h K_ii is below 1, so the trace of B is below p: a sphere's
// one point and a box's four corners landing flat (B's eigenvalues
// 1, 1.5, 1.5 and 0 when saturated) stay inside it, but three points of an
// uneven face of a light hull, overdamped (restitution 0), reached
// lambda_max(B) = 1.86 on a rocking mode, whose velocity then flipped sign
// every sub-step (docs/methods/penalty.md, "Resting hulls").
//
// Where lambda_max(B) > kMaxShare, every normal dashpot of the pair is
// scaled by kMaxShare / lambda_max(B) (its largest mode then loses
// kMaxShare of its velocity a sub-step, the others less). B is formed once
// a step over the pair's engaged points at n_b = 1 (the largest c_i' a
// sub-step can give them) and rescaled in each sub-step for that
// sub-step's n_b: B(n_b) = D B(1) D with D^2 = diag((1 + a_i) / (1 + n_b
// a_i)), a_i = h c_i K_ii, so lambda_max(B(n_b)) <= lambda_max(B(1))
// (1 + a) / (1 + n_b a) with a the pair's least a_i. Counted at n_b = 1
// throughout, the bound cut the pairs of loads on a jointed plank that
// their n_b already held below it, and they crept past their bound.
// It is formed only for pairs with two points touching at the step's
// start whose trace, then Gershgorin bound, at that start's n_b pass
// kMaxShare (a busy body's pairs, as the pyramid's, end there: forming it
// for every pair cost the pyramid 9% of its instructions).
// lambda_max by power iteration (Golub and Van Loan, "Matrix Computations",
// 8.2.1), exact for p = 2.
#pragma once

#include <vector>

#include "service/contact/penalty/penalty_row.h"
#include "service/physics/world.h"

namespace contactsim {

class PenaltyDampingBound {
 public:
  // the largest share of a mode's velocity a pair's dashpots may take in a
  // sub-step: below 2 - (omega h)^2 / 2 at the omega h <= 1 of the
  // sub-step count (penalty_explicit.h), and above a box's 1.5
  static constexpr double kMaxShare = 1.5;

  // Each engaged pair's lambda_max(B) with n_b = 1, for sub-steps of h
  // (linear law; none otherwise).
  void Prepare(const World& world, const std::vector<PenaltyRow>& rows, double h, bool linear);
  // The scale of row k's cut dashpot in a sub-step whose n_b is `shared`.
  double Scale(size_t k, double shared) const {
    return bounds_.empty() || bounds_[k].share <= kMaxShare ? 1.0 : BoundedScale(k, shared);
  }

 private:
  // a pair's lambda_max(B) at n_b = 1 and its least h c_i K_ii, per row
  // (share 0: within the bound)
  struct Bound {
    double share = 0.0, least = 0.0;
  };
  // a point of the pair being bounded: its normal from the pair's lower
  // body index to the higher, the angular parts of J on each (r x n) and
  // of M^-1 J^T (I^-1 (r x n)), zero on a body that is not dynamic
  struct Point {
    Vec3 n, jl, jh, kl, kh;
  };

  // the pair's Bound where B at the step's start n_b (`shared`) may pass
  // kMaxShare, else share 0
  Bound PairBound(const World& world, const std::vector<PenaltyRow>& rows, const int* points, int p, double h,
                  double shared);
  double LargestEigenvalue(int p);
  double BoundedScale(size_t k, double shared) const;
  // the body's I^-1 in the world frame, formed once a step (zero if it is
  // not dynamic)
  const Mat3& InvInertia(const World& world, int body);

  std::vector<Bound> bounds_;       // per row
  std::vector<int> touching_;       // per pair: its points touching at the step's start
  std::vector<double> shared_;      // per body: n_b at the step's start
  std::vector<int> start_, order_;  // rows grouped by pair: order_[start_[q] .. start_[q + 1])
  std::vector<Point> points_;
  std::vector<Mat3> inv_inertia_;   // per body, where inertia_set_
  std::vector<char> inertia_set_;
  std::vector<double> a_, w_, k_, b_, u_;  // per point, p x p matrices, power iteration vectors
};

}  // namespace contactsim
