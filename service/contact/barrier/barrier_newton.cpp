// The Newton iterations of BarrierSolver (barrier_solver.h), solved island
// by island. The incremental potential is a sum of terms of one body
// (inertia, orthogonality) and of two (a barrier pair, a friction pair), so
// along a Newton step bodies that no pair of the step's line joins are
// separable: each connected set ("island") has its own line search (its
// own CCD bound and energy decrease, Li et al. 2020, IPC Alg. 1, applied
// per island) and its own convergence test. An island whose Newton step is
// below the tolerance has converged and leaves the active set; it is solved
// again only when a body it shares a pair with moves, or kappa changes
// under its barrier pairs. So a landing box's small CCD steps no longer
// hold back the bodies falling freely beside it, and a converged body is
// neither assembled nor factorised again (Lan et al. 2022, Affine Body
// Dynamics, solve the same block structure).
#include <algorithm>
#include <cmath>
#include <limits>

#include "service/contact/barrier/additive_ccd.h"
#include "service/contact/barrier/barrier_potential.h"
#include "service/contact/barrier/barrier_solver.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// Bound on how far any point of a body of radius r moves under the step dq.
double MotionBound(const Vec12& dq, double r) { return dq.head<3>().norm() + dq.tail<9>().norm() * r; }

// g += G grad and H += G hess G^T for a term with gradient directions Ga
// (slot sa) and Gb (slot sb; -1 for a body not solved), hess >= 0.
template <typename G, typename Grad, typename Hess>
void AddTerm(NewtonSystem* system, int sa, int sb, const G& Ga, const G& Gb, const Grad& grad, const Hess& hess) {
  if (sa >= 0) {
    system->Gradient(sa) += Ga * grad;
    system->Diagonal(sa).noalias() += Ga * hess * Ga.transpose();
  }
  if (sb >= 0) {
    system->Gradient(sb) += Gb * grad;
    system->Diagonal(sb).noalias() += Gb * hess * Gb.transpose();
  }
  if (sa >= 0 && sb >= 0) {
    const Mat12 cross = Ga * hess * Gb.transpose();
    bool transposed = false;
    Mat12& block = system->Coupling(sa, sb, &transposed);
    if (transposed) {
      block += cross.transpose();
    } else {
      block += cross;
    }
  }
}

}  // namespace

void BarrierSolver::ActivateAll() {
  for (Body& b : bodies_) b.active = b.dof >= 0;
}

int BarrierSolver::AssignSlots() {
  int n = 0;
  for (Body& b : bodies_) b.slot = b.active ? n++ : -1;
  return n;
}

void BarrierSolver::Assemble(const std::vector<Entry>& entries, NewtonSystem* system) const {
  const double h2 = h_ * h_, eps = params_.eps_v * h_;
  for (const Body& b : bodies_) {
    if (b.slot < 0) continue;
    Vec12 go;
    Mat12 Ho;
    OrthogonalityDerivatives(b.q, b.k_ortho, &go, &Ho);
    system->Gradient(b.slot) = b.mass.Times(b.q - b.q_pred) + h2 * go;
    system->Diagonal(b.slot) = b.mass.Matrix() + h2 * Ho;
  }
  for (const Entry& e : entries) {
    const int sa = bodies_[e.a].slot, sb = bodies_[e.b].slot;
    const double d = EffectiveDistance(e), w = e.width;
    if (d >= w || (sa < 0 && sb < 0)) continue;
    const Vec12 Ga = -AffineJacobianT(e.dist.Xa, e.dist.n);
    const Vec12 Gb = AffineJacobianT(e.dist.Xb, e.dist.n);
    // kappa m(x) b(d): the product rule adds kappa b grad m (edge-edge);
    // the Hessian keeps the PSD Gauss-Newton part kappa m b'' grad d grad d^T
    const double m = e.mollifier.m, k = kappa_ * e.scale;
    AddTerm(system, sa, sb, Ga, Gb, Eigen::Matrix<double, 1, 1>(h2 * k * m * BarrierFirstDerivative(d, w)),
            Eigen::Matrix<double, 1, 1>(h2 * k * m * BarrierSecondDerivative(d, w)));
    if (m < 1.0) {
      const double kb = h2 * k * Barrier(d, w);
      if (sa >= 0) system->Gradient(sa) += kb * e.mollifier.grad_a;
      if (sb >= 0) system->Gradient(sb) += kb * e.mollifier.grad_b;
    }
  }
  for (const Friction& f : friction_) {
    const Body& A = bodies_[f.a];
    const Body& B = bodies_[f.b];
    if (A.slot < 0 && B.slot < 0) continue;
    const Vec3 rel = (AffinePoint(B.q, f.Xb) - AffinePoint(B.q0, f.Xb)) - (AffinePoint(A.q, f.Xa) - AffinePoint(A.q0, f.Xa));
    const Eigen::Vector2d u = f.T.transpose() * rel;
    const double y = u.norm();
    const double w = h2 * f.mu_lambda * FrictionF1OverY(y, eps);
    // Hessian of mu lambda f0(|u|) in u (IPC appendix): f1/y I +
    // (f1' y - f1) / y^3 u u^T; PSD for the f1 of barrier_potential.h:
    // for y >= eps it is (I - u u^T / y^2) / y, below eps
    // f1/y I - u u^T / (eps^2 y). (Its curvature along u jumps from 0
    // while sliding to 2/eps once held, so a contact going from slip to
    // stick overshoots and the line search cuts alpha; the IRLS weight
    // f1/y I, which majorises f0, removed that but stopped Newton early
    // on a sliding box: BENCHMARKS.md, "barrier".)
    Eigen::Matrix2d hess = w * Eigen::Matrix2d::Identity();
    if (y >= eps) {
      hess -= (w / (y * y)) * u * u.transpose();
    } else if (y > 1e-12 * eps) {
      hess -= (h2 * f.mu_lambda / (eps * eps * y)) * u * u.transpose();
    }
    Eigen::Matrix<double, 12, 2> Ga, Gb;
    for (int k = 0; k < 2; ++k) {
      Ga.col(k) = -AffineJacobianT(f.Xa, f.T.col(k));
      Gb.col(k) = AffineJacobianT(f.Xb, f.T.col(k));
    }
    AddTerm(system, A.slot, B.slot, Ga, Gb, Eigen::Vector2d(w * u), hess);
  }
}

std::vector<BarrierSolver::Island> BarrierSolver::Islands(const std::vector<Entry>& line,
                                                          const std::vector<Entry>& entries) {
  const int n = static_cast<int>(bodies_.size());
  UnionFind sets(n);
  auto join = [&](int a, int b) {
    if (bodies_[a].active && bodies_[b].active) sets.Join(a, b);
  };
  for (const Entry& e : line) join(e.a, e.b);
  for (const Entry& e : entries) join(e.a, e.b);
  for (const Friction& f : friction_) join(f.a, f.b);
  // islands in the order of their first body
  std::vector<Island> islands;
  std::vector<int> island_of(n, -1);
  for (int i = 0; i < n; ++i) {
    if (!bodies_[i].active) continue;
    const int root = sets.Root(i);
    if (island_of[root] < 0) {
      island_of[root] = static_cast<int>(islands.size());
      islands.emplace_back();
    }
    island_of[i] = island_of[root];
    islands[island_of[i]].bodies.push_back(i);
  }
  // each pair goes to the island of its active body (both: the same one)
  auto owner = [&](int a, int b) { return bodies_[a].active ? island_of[a] : bodies_[b].active ? island_of[b] : -1; };
  for (size_t k = 0; k < line.size(); ++k) {
    const int i = owner(line[k].a, line[k].b);
    if (i >= 0) islands[i].line.push_back(static_cast<int>(k));
  }
  for (size_t k = 0; k < friction_.size(); ++k) {
    const int i = owner(friction_[k].a, friction_[k].b);
    if (i >= 0) islands[i].friction.push_back(static_cast<int>(k));
  }
  return islands;
}

double BarrierSolver::IslandEnergy(const Island& island, const std::vector<Entry>& line) const {
  double inertia = 0.0, potential = 0.0;
  for (int i : island.bodies) {
    const Body& b = bodies_[i];
    const Vec12 dq = b.q - b.q_pred;
    inertia += 0.5 * dq.dot(b.mass.Times(dq));
    potential += OrthogonalityEnergy(b.q, b.k_ortho);
  }
  for (int k : island.line) {
    const Entry& e = line[k];
    const Body& A = bodies_[e.a];
    const Body& B = bodies_[e.b];
    const Mat3 Aa = AffineMatrix(A.q), Ab = AffineMatrix(B.q);
    const PairDistance d =
        EvaluatePair(A.geometry, AffinePosition(A.q), Aa, B.geometry, AffinePosition(B.q), Ab, e.pair, e.depth,
                     {e.shift, e.width});
    const double b = Barrier(d.d - e.shift, e.width);
    if (!std::isfinite(b)) return std::numeric_limits<double>::infinity();
    if (b == 0.0) continue;
    potential += kappa_ * e.scale * MollifyEdgeEdge(A.geometry, Aa, B.geometry, Ab, e.pair, d).m * b;
  }
  const double eps = params_.eps_v * h_;
  for (int k : island.friction) {
    const Friction& f = friction_[k];
    const Body& A = bodies_[f.a];
    const Body& B = bodies_[f.b];
    const Vec3 rel = (AffinePoint(B.q, f.Xb) - AffinePoint(B.q0, f.Xb)) - (AffinePoint(A.q, f.Xa) - AffinePoint(A.q0, f.Xa));
    potential += f.mu_lambda * FrictionF0((f.T.transpose() * rel).norm(), eps);
  }
  return inertia + h_ * h_ * potential;
}

bool BarrierSolver::LineSearch(const Island& island, const std::vector<Vec12>& step, const std::vector<Entry>& line) {
  // the CCD bound over the island's pairs, then halving until the energy decreases
  double alpha = 1.0;
  for (int k : island.line) alpha = AdditiveCcd(CcdPairOf(line[k], step), params_.ccd_fraction, alpha);
  const double e0 = IslandEnergy(island, line);
  std::vector<Vec12> start;
  for (int i : island.bodies) start.push_back(bodies_[i].q);
  bool accepted = false;
  for (int halving = 0; halving < 40; ++halving, alpha *= 0.5) {
    for (size_t k = 0; k < island.bodies.size(); ++k) {
      Body& b = bodies_[island.bodies[k]];
      b.q = start[k] + alpha * step[b.dof];
    }
    if (IslandEnergy(island, line) <= e0) {
      accepted = true;
      break;
    }
  }
  if (!accepted) {
    for (size_t k = 0; k < island.bodies.size(); ++k) bodies_[island.bodies[k]].q = start[k];
  }
  return accepted;
}

bool BarrierSolver::AdvanceIslands(const std::vector<Vec12>& step, bool converge, std::vector<Entry>* line,
                                   std::vector<Entry>* entries, double* last_min) {
  Collect(&step, line);
  const std::vector<Island> islands = Islands(*line, *entries);
  std::vector<char> moved(bodies_.size(), 0);
  bool stuck = false;
  for (const Island& island : islands) {
    double fastest = 0.0;
    for (int i : island.bodies) fastest = std::max(fastest, MotionBound(step[bodies_[i].dof], bodies_[i].radius) / h_);
    // converged: every vertex would move slower than the tolerance
    if (converge && fastest < params_.tolerance) {
      for (int i : island.bodies) bodies_[i].active = false;
      continue;
    }
    if (fastest == 0.0) continue;
    if (LineSearch(island, step, *line)) {
      for (int i : island.bodies) moved[i] = 1;
    } else if (converge) {
      stuck = true;   // no alpha decreased its energy: it stops here
      for (int i : island.bodies) bodies_[i].active = false;
    }
  }
  Refresh(*line, entries);

  // adaptive kappa: double it while the closest pair keeps closing below
  // the floor (the line's candidates hold every pair within d_hat of a
  // body that moved)
  double min_d = std::numeric_limits<double>::infinity();
  // (a shifted pair that was apart at the step's start by its true
  // distance d: in shifted terms it never gets below the floor, and one
  // that ended a sphere_pile step 3 um apart sank to d = -9.8 um in the
  // next; placed pairs do not count: their zero lies a width below where
  // they were placed, and under load they rest near it by design,
  // barrier_solver.h)
  for (const Entry& e : *entries) {
    if (!e.placed) min_d = std::min(min_d, e.apart ? e.dist.d : EffectiveDistance(e));
  }
  const double kappa_before = kappa_;
  if (min_d < kFloor * params_.d_hat && min_d < *last_min) kappa_ = std::min(kappa_max_, 2.0 * kappa_);
  *last_min = min_d;
  WakeNeighbours(*line, moved, kappa_ != kappa_before, entries);
  return stuck;
}

void BarrierSolver::WakeNeighbours(const std::vector<Entry>& line, const std::vector<char>& moved, bool kappa_changed,
                                   std::vector<Entry>* entries) {
  bool woke = false;
  auto wake = [&](int from, int to) {
    Body& b = bodies_[to];
    if (moved[from] && b.dof >= 0 && !b.active) b.active = woke = true;
  };
  for (const Entry& e : line) wake(e.a, e.b), wake(e.b, e.a);
  for (const Friction& f : friction_) wake(f.a, f.b), wake(f.b, f.a);
  if (kappa_changed) {
    // a new kappa moves every barrier pair's minimum: every body with a pair
    // within d_hat is solved again
    std::vector<char> was(bodies_.size());
    for (size_t i = 0; i < bodies_.size(); ++i) was[i] = bodies_[i].active;
    ActivateAll();
    Collect(nullptr, entries);
    std::vector<char> touching(bodies_.size(), 0);
    for (const Entry& e : *entries) touching[e.a] = touching[e.b] = 1;
    for (size_t i = 0; i < bodies_.size(); ++i) bodies_[i].active = bodies_[i].active && (was[i] || touching[i]);
    return;
  }
  // the woken bodies' pairs with bodies that stayed frozen
  if (woke) Collect(nullptr, entries);
}

void BarrierSolver::StartTurningBodiesAtPrediction(std::vector<Vec12>* step, std::vector<Entry>* line,
                                                   std::vector<Entry>* entries, double* last_min) {
  bool turning = false;
  for (const Body& b : bodies_) {
    if (b.dof < 0) continue;
    Vec12& s = (*step)[b.dof];
    s = b.q_pred - b.q;
    // (where the tangent step's stretch, r |dA|^2 / 2 at a vertex, is below
    // what Newton resolves, it starts at q_n as well)
    const double turn = s.tail<9>().norm();
    if (0.5 * b.radius * turn * turn < params_.tolerance * h_) {
      s.setZero();
    } else {
      turning = true;
    }
  }
  if (turning) AdvanceIslands(*step, false, line, entries, last_min);
}

void BarrierSolver::Minimise(std::vector<Entry>* entries, double* last_min, BarrierStepResult* result) {
  result->converged = false;
  if (dofs_ == 0) return;
  std::vector<Vec12> step(dofs_), dq;
  std::vector<Entry> line;
  bool stuck = false;
  for (int it = 0; it < params_.max_iterations; ++it) {
    if (AssignSlots() == 0) {
      result->converged = !stuck;
      return;
    }
    system_.Reset(AssignSlots());
    Assemble(*entries, &system_);
    if (!system_.Solve(&dq)) return;
    ++result->iterations;
    for (const Body& b : bodies_) {
      if (b.dof >= 0) step[b.dof] = b.slot >= 0 ? dq[b.slot] : Vec12::Zero();
    }
    stuck = AdvanceIslands(step, true, &line, entries, last_min) || stuck;
  }
  // (the last iteration may have converged every island)
  if (AssignSlots() == 0) result->converged = !stuck;
}

}  // namespace contactsim
