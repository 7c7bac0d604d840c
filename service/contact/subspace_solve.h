// A direct solve of the normal and joint rows of the components that have
// a large mass ratio, after the Gauss-Seidel sweeps of a velocity or
// split-impulse solve: projected Gauss-Seidel subspace minimisation
// (Silcowitz, Niebe and Erleben, "Interactive rigid body dynamics using a
// projected Gauss-Seidel subspace minimization method", VISIGRAPP 2010).
//
// Why: Gauss-Seidel on A = J M^-1 J^T converges at a rate set by A's
// conditioning, and a heavy body on a light one makes it ill-conditioned:
// the light body's rows are ~ 1/m_light stiff, the heavy body's ~ 1/m_heavy,
// and each sweep moves the heavy body's share of the error by about
// m_light / m_heavy (Erleben, "Velocity-based shock propagation", ACM TOG
// 2007). A 20 kg box on a 0.02 kg box left 20-30 sweeps far from the
// answer and sank through the light box within 3 s. The sweeps still find
// which rows push (the active set) and the friction impulses; given those,
// the rows that push, and the friction rows that stick, solve a linear
// system exactly:
//   (A_SS + C_S) dlambda_S = rhs_S - J_S v - C_S lambda_S,   S = the free rows,
// C the diagonal of the rows' compliances (ConstraintRow::cfm; 0 for rigid rows),
// with the rows at a bound (sliding friction among them) held. Sticking
// friction is in S because its rows converge as slowly: without it a 20 kg
// box on a 0.02 kg one crept 44 mm sideways in 2 s. Rows the solution
// pushes past a bound are held there and S solved again; a held row that
// the solution makes approach (J v < rhs) joins S again (a principal
// pivoting pass, Judice and Pires 1994), `passes` times at most. With
// `start_free` every row starts free, and the impulses move toward each
// solution only as far as every row stays within its bounds (a friction
// row's bound moves with its normal's impulse); the row that stops them is
// held (a feasible active-set step, Nocedal and Wright, "Numerical
// Optimization", 16.5).
//
// A is sparse (rows couple through the bodies they share), scaled to unit
// diagonal (Jacobi) and solved for the minimum-norm solution
// (min_norm_solve.h): a face's four coplanar contact
// points make A singular (rank 3 per face), and the minimum-norm answer
// spreads the load evenly as the xpbd method's pair solve does.
//
// The sweeps can leave a component far from any answer: warm-started with
// the large opposing impulses that hold a heavy body on a light one, twenty
// sweeps took a 0.1 kg box under a 10 kg sphere from 77 J to 2,400 J, and
// the active set they left let the direct solve keep 535 J of it (a box
// thrown at 90 m/s). A contact solve adds no kinetic energy beyond what its
// targets ask for: with impulses lambda, T_after - T_before =
// lambda^T (J v_before + A lambda / 2), which at a solution is
// lambda^T (J v_before + rhs) / 2 <= sum max(0, lambda_i rhs_i) where rows
// approach (Moreau's passivity of a velocity-level contact solve). So when
// a component ends with more kinetic energy than it had before this solve's
// impulses (read back from SolverBody::dP and dL) plus that allowance, its
// impulses are set to zero and it is solved again from every row free by
// feasible steps (start_free), which lower the solve's quadratic objective
// at every step and so cannot gain energy.
//
// Only components (dynamic bodies joined by rows) whose heaviest body is at
// least `mass_ratio` times their lightest are solved, and only up to
// `max_rows` rows: equal-mass scenes, where the sweeps converge, pay one
// pass over the bodies (MassRatioReached) and keep their results bit for
// bit.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/min_norm_solve.h"

namespace contactsim {

struct SubspaceOptions {
  double mass_ratio = 10.0;  // heaviest / lightest dynamic body of a component that gets the solve; 0 = off
  int max_rows = 300;        // larger components keep the sweeps' answer
  int passes = 8;            // active-set passes at most
  // Start with every row free rather than with the rows the sweeps left at
  // a bound held, and take feasible steps: for the soft step, whose one
  // sweep a sub-step leaves a 1:1000 component's impulses at bounds they do
  // not belong at (the supports of an aligned plank spun out for light
  // masses of 0.03-10 kg; docs/physics.md, "Mass ratios"). It holds one row
  // a pass, so it wants more passes. The twenty sweeps of impulse and lcp
  // leave a better active set: with feasible steps lcp let three of 96
  // heavy-on-light box stacks fall, against none.
  bool start_free = false;
  // Re-solve from zero impulses a component that ends with more kinetic
  // energy than it had before the solve (see above; "before" is what
  // SolverBody::dP and dL say the bodies were before their impulses); off
  // for rows that move positions (pseudo-velocities), whose energy means
  // nothing.
  bool energy_guard = true;
  int restart_passes = 64;  // active-set passes at most in that re-solve
  // Let a held friction row rejoin the free rows when the solution leaves it
  // inside mu times its normal's impulse or slipping the way it pushes, as
  // a held normal row rejoins (otherwise sliding friction stays held). With
  // start_free, the first steps from a sweep that left a point sliding hold
  // its friction at the bound within a small step, before the normals
  // settle; kept held, a box on a welded slope slid 0.8-19 mm in 3 s under
  // the soft step (docs/methods/soft.md, "Jointed supports").
  bool release_friction = false;
  // Per body (optional): a component holding a marked body is solved
  // whatever its mass ratio. The methods mark the jointed bodies that a
  // contact touches, with the joint rows among `rows` (jointed_contacts.h).
  const std::vector<char>* always = nullptr;
};

struct SubspaceReport {
  int components = 0;  // components solved directly
  int rows = 0;        // rows in them
  int passes = 0;      // active-set passes summed over them
  int restarts = 0;    // components re-solved from zero by the energy guard
};

class SubspaceSolver {
 public:
  // rows: lambda holds the sweeps' impulses, which `bodies` already carry.
  // Every row of a selected component is solved: friction rows (normal_row
  // >= 0) while they stick, |lambda| < mu lambda_normal, and held where they
  // slide. Changes go to bodies via ConstraintRow::Apply (v, w, dP, dL).
  SubspaceReport Solve(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                       const SubspaceOptions& options);
  // Whether any two dynamic bodies differ in mass by `ratio` or more: when
  // not, no component can, and callers skip building rows (one pass over
  // the bodies; it kept the pyramid's step time unchanged). Callers with
  // SubspaceOptions::always set solve regardless.
  static bool MassRatioReached(const std::vector<SolverBody>& bodies, double ratio);

 private:
  // Solves the component whose rows are `members` (indices in rows).
  int SolveComponent(const std::vector<int>& members, std::vector<ConstraintRow>& rows,
                     std::vector<SolverBody>& bodies, int passes, bool start_free);

  // The kinetic energy of the members' dynamic bodies now (`before` false)
  // or before this solve's impulses (true: v - M^-1 dP, w - I^-1 dL).
  double KineticEnergy(const std::vector<int>& members, const std::vector<ConstraintRow>& rows,
                       const std::vector<SolverBody>& bodies, bool before);
  // Whether the members left their bodies with more kinetic energy than
  // `start` plus what their targets allow (sum of max(0, lambda rhs)) and
  // a relative 1e-3 of round-off.
  bool GainedEnergy(const std::vector<int>& members, const std::vector<ConstraintRow>& rows,
                    const std::vector<SolverBody>& bodies, double start);

  // A = J M^-1 J^T over the members (sparse: rows couple through shared
  // bodies) into A_ and its diagonal into diag_.
  void BuildCoupling(const std::vector<int>& members, const std::vector<ConstraintRow>& rows,
                     const std::vector<SolverBody>& bodies);

  // The free rows' impulses plus dl, or, where that leaves a row's bounds,
  // every such row held at the bound it passed and nothing else changed;
  // true when rows were held.
  bool ClampPastBounds(const std::vector<int>& members, const std::vector<int>& free_rows,
                       const Eigen::VectorXd& dl, std::vector<char>& held, std::vector<ConstraintRow>& rows,
                       std::vector<SolverBody>& bodies);
  // The free rows' impulses moved along dl as far as all stay within their
  // bounds (LongestStep), the row that stops them held at its bound; true
  // when a row was held.
  bool StepWithinBounds(const std::vector<int>& members, const std::vector<int>& free_rows,
                        const Eigen::VectorXd& dl, std::vector<char>& held, std::vector<ConstraintRow>& rows,
                        std::vector<SolverBody>& bodies);

  // How far (0..1) the free rows' impulses may move along dl before one
  // leaves its bounds (a friction row's bound moves with its normal's
  // impulse), and which free row (index into free_rows) stops them, or -1.
  struct Step {
    double alpha = 1.0;
    int blocking = -1;
  };
  Step LongestStep(const std::vector<int>& members, const std::vector<int>& free_rows, const Eigen::VectorXd& dl,
                   const std::vector<ConstraintRow>& rows) const;

  // Brings held friction rows inside mu times their normal's impulse.
  void ClampHeldFriction(const std::vector<int>& members, const std::vector<char>& held,
                         std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies);

  bool release_friction_ = false;  // this Solve's option
  std::vector<int> root_of_row_;
  std::vector<int> member_of_;  // per row: its index in the component's members, or -1
  std::vector<int> position_;   // per member: its index among the free rows, or -1
  std::vector<std::vector<int>> body_rows_;  // per body: the members on it
  std::vector<int> seen_;                    // per member: the last row coupled with it
  std::vector<int> counted_;                 // per body: the last KineticEnergy call that summed it
  int energy_calls_ = 0;
  std::vector<Eigen::Triplet<double>> triplets_;
  std::vector<int> cursor_;  // FillColumns' next place in each column
  Eigen::SparseMatrix<double> A_;
  Eigen::SparseMatrix<double> free_block_;  // the Jacobi-scaled A of a pass's free rows
  Eigen::VectorXd diag_;
  MinNormCache min_norm_cache_;  // symbolic analyses of the components' patterns
};

}  // namespace contactsim
