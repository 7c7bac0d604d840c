// BarrierSolver::BalanceMomentum (barrier_solver.h): the momentum of a
// cluster of dynamic bodies that touches no fixed body.
//
// At the minimum of the incremental potential the gradient vanishes; its
// translation rows summed over a cluster are sum_i m_i (p_i - p_pred,i)
// plus h^2 times the pair forces, which cancel pairwise (every barrier and
// friction term depends on p_b - p_a only). So implicit Euler keeps such a
// cluster's momentum exactly: sum_i m_i (p_i - p_pred,i) = 0. Newton's
// iterates do not: a line search's alpha < 1 leaves part of the residual,
// and a body frozen with its converged island acts on the active ones as a
// fixed wall (barrier_newton.cpp). A step that stops at max_iterations keeps
// that residual; a rack of 16 touching balls broken at 3 m/s lost 30% of
// its momentum in the two impact steps (docs/methods/barrier.md).
// Moving the whole cluster by one translation changes none of its pair
// distances, and the one that zeroes the sum restores its momentum.
// Clusters join the pairs within d_hat at the step's start as well as at
// its end: a ball that leaves the rack within the step has no pair at the
// end, yet Newton's residual from its pair during the step stays with it
// (4.6e-2 s into the break, 6e-6 of the momentum); in one cluster with the
// rack the sum over both is restored.
#include <cmath>
#include <utility>
#include <vector>

#include "service/contact/barrier/barrier_solver.h"
#include "service/contact/union_find.h"

namespace contactsim {

bool BarrierSolver::BalanceMomentum(std::vector<std::pair<int, int>> pairs, const std::vector<Entry>& entries) {
  const int n = static_cast<int>(bodies_.size());
  UnionFind sets(n);
  auto dynamic = [&](int i) { return bodies_[i].dof >= 0; };
  for (const Entry& e : entries) pairs.emplace_back(e.a, e.b);
  for (const Friction& f : friction_) pairs.emplace_back(f.a, f.b);
  for (const auto& [a, b] : pairs) {
    if (dynamic(a) && dynamic(b)) sets.Join(a, b);
  }
  // a cluster with a pair to a fixed body takes that body's reaction, which
  // only the minimum gives; a body without pairs has no pair forces to balance
  std::vector<char> held(n, 0), paired(n, 0);
  for (const auto& [a, b] : pairs) {
    if (!dynamic(a) || !dynamic(b)) held[sets.Root(dynamic(a) ? a : b)] = 1;
    paired[sets.Root(a)] = paired[sets.Root(b)] = 1;
  }
  std::vector<Vec3> excess(n, Vec3::Zero());
  std::vector<double> mass(n, 0.0);
  for (int i = 0; i < n; ++i) {
    if (!dynamic(i)) continue;
    const Body& b = bodies_[i];
    excess[sets.Root(i)] += b.mass.m * (b.q - b.q_pred).head<3>();
    mass[sets.Root(i)] += b.mass.m;
  }
  // every other body is at least d_hat from the cluster (else a pair would
  // join or hold it), so a shift below d_hat / 2 keeps every gap open even
  // when two clusters move towards each other
  bool moved = false;
  for (int i = 0; i < n; ++i) {
    if (!dynamic(i)) continue;
    const int root = sets.Root(i);
    if (held[root] || !paired[root]) continue;
    const Vec3 shift = -excess[root] / mass[root];
    if (shift.norm() >= 0.5 * params_.d_hat) continue;
    bodies_[i].q.head<3>() += shift;
    moved = true;
  }
  return moved;
}

}  // namespace contactsim
