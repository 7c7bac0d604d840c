// The implicit cut of the penalty dashpots (penalty_explicit.h, stage 2)
// where one body pair holds more points than one manifold: a compound
// body's children each bring theirs (shape.h), a table's four legs sixteen.
//
// Stage 2 integrates each point's dashpot c_i implicitly against the
// point's own inverse effective mass K_ii, c_i' = c_i / (1 + h c_i K_ii).
// An overdamped dashpot (restitution 0) then saturates at c_i' ~ 1 / (h
// K_ii), whatever its share c / nc, so the pair's points together take
// h sum_i c_i' ~ sum_i 1 / K_ii of the body's approach a sub-step. For a
// face's four corners that is about half the body's mass (a corner's K_ii
// holds its turn as well); for the sixteen feet of a table or a slab split
// into four children, whose inner points turn it little, it was 1.9 times
// the mass: the dashpots reversed the approach within one sub-step and a
// table dropped with e = 0 bounced from 0.10 m to 0.94 m.
//
// The points push one rigid pair, so each point's velocity answers the
// others' dashpots too. The normal dashpots of such a pair are integrated
// implicitly together: with C = diag(c_i) and K_ij = J_i M^-1 J_j^T
// (normal_block.h's K, lever arms of the step's start), the dashpot forces
// at the sub-step's end velocities, f = -C (v + h K f), are
//   f = -(C^-1 + h n_b K)^-1 v,
// n_b the pairs of the busier body as in stage 2; for one point it is
// stage 2's -c v / (1 + h n_b c K). Every mode of the pair is then damped
// without overshoot: cut point by point, a slab split into two children
// rocked about its long axis at 0.027 rad/s for good, its eight points'
// cut dashpots taking 4.7 times the rocking's velocity a sub-step (the
// unilateral contacts bounded the growth), and an L of two boxes rocked
// at 0.03 rad/s. A dense solve of the touching points, p^3 / 3 for p
// points (16 for a table), only for these pairs.
// The friction dashpots ct take a cut along the mode in which every point
// slips alike: each point's ct / (1 + h n_b max(ct K_ii, sum_j ct_j K_ij))
// along its slip direction, which for one point is stage 4's.
// Only pairs with a compound body take this path (their points come from
// several manifolds); the rest are stepped as before, bit for bit.
#pragma once

#include <vector>

#include "service/contact/penalty/penalty_row.h"
#include "service/physics/world.h"

namespace contactsim {

class PenaltyPairDamping {
 public:
  // The rows' responses at the step's start (lever arms and inertias of
  // `world` now), for rows of pairs with a compound body.
  void Prepare(const World& world, const std::vector<PenaltyRow>& rows);
  bool active() const { return active_; }
  bool Coupled(size_t k) const { return active_ && responses_[k].coupled; }

  // One pass: the rows that touch (`touching` per row, with rows[k].law.c
  // and vn0 of this pass) give each coupled row its normal dashpot force
  // and the friction dashpots' sums; `shared` is n_b per row.
  void Solve(const std::vector<PenaltyRow>& rows, const std::vector<char>& touching,
             const std::vector<double>& shared, double h);
  // Row k's normal dashpot force of this pass (N, along n on B; > 0 pushes
  // when approaching).
  double NormalForce(size_t k) const { return force_[k]; }
  // sum_j ct_j K_kj along the slip directions (1/s), over this pass's
  // touching rows with friction.
  double Tangent(size_t k) const;

 private:
  // One direction of a row: d, and J's angular parts and their responses,
  // r x d and I^-1 (r x d), on A and B (zero for a body that is not dynamic).
  struct Direction {
    Vec3 d = Vec3::Zero();
    Vec3 ja = Vec3::Zero(), jb = Vec3::Zero(), ia = Vec3::Zero(), ib = Vec3::Zero();
  };
  struct Response {
    bool coupled = false;
    int pair = -1;          // PenaltyRow::pair
    double inv_mass = 0.0;  // 1/kg, 1/m_A + 1/m_B of the dynamic ones
    Direction normal, slip;
  };
  // per pair, the sums of ct_j d_j and ct_j I^-1 (r_j x d_j) on A and B
  struct Sums {
    Vec3 lin = Vec3::Zero(), ang_a = Vec3::Zero(), ang_b = Vec3::Zero();
  };
  static double Row(const Response& r, const Direction& d, const Sums& s);
  static void Accumulate(const Direction& d, double c, Sums* s);

  void SolvePair(const std::vector<PenaltyRow>& rows, const std::vector<int>& points, double shared, double h);

  bool active_ = false;
  std::vector<Response> responses_;  // per row
  std::vector<Sums> slip_;           // per pair
  std::vector<double> force_;        // per row
  std::vector<std::vector<int>> touching_;  // per pair: its touching coupled rows this pass
};

}  // namespace contactsim
