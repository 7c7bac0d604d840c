// The linear system of one Newton iteration of the barrier method,
// H dq = -g (barrier_solver.h), over the 12-DOF blocks of the bodies being
// solved ("slots"), assembled in dense 12x12 blocks: a diagonal block per
// slot and a coupling block per pair of slots that some term joins.
//
// Solved per connected component of the coupling graph: no term couples two
// components, so H is block diagonal over them and each is its own system
// (the islands of Lan et al. 2022, Affine Body Dynamics, whose solver
// exploits the same block structure). A lone body, the common case in a
// scene of falling bodies, is one dense 12x12 LDL^T; a component of n > 1
// bodies a sparse LDL^T of its own 12n unknowns (Eigen's SimplicialLDLT,
// AMD ordering), so the cost follows the contact graph instead of the
// whole scene. Only the lower triangle is handed to the factorisation.
// H is symmetric positive definite (M plus PSD projections), so both
// factorisations are stable without pivoting.
#pragma once

#include <unordered_map>
#include <vector>

#include "service/contact/barrier/affine_body.h"

namespace contactsim {

class NewtonSystem {
 public:
  // `slots` blocks, all zero, and no couplings.
  void Reset(int slots);
  int slots() const { return static_cast<int>(gradient_.size()); }
  Vec12& Gradient(int slot) { return gradient_[slot]; }
  Mat12& Diagonal(int slot) { return diagonal_[slot]; }
  // H's block (r, c) for r != c; the block (c, r) is its transpose. Zero
  // when first asked for.
  Mat12& Coupling(int r, int c, bool* transposed);
  // dq (one Vec12 per slot); false when a factorisation failed (then dq
  // holds the components solved before it and zeros).
  bool Solve(std::vector<Vec12>* dq);

 private:
  bool SolveComponent(const std::vector<int>& slots, std::vector<Vec12>* dq);

  std::vector<Vec12> gradient_;
  std::vector<Mat12> diagonal_;
  std::vector<std::pair<int, int>> coupled_;   // (r, c), r < c, in the order first asked for
  std::vector<Mat12> coupling_;                // block (r, c) of each
  std::unordered_map<long long, int> index_;   // r * slots + c -> place in coupled_
  std::vector<std::vector<int>> incident_;     // per slot, its places in coupled_
};

}  // namespace contactsim
