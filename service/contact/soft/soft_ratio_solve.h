// The soft step's contacts where a heavy body rests on a light one
// (docs/methods/soft.md, "Heavy on light"; docs/physics.md, "Mass ratios").
//
// Two things go wrong there under the plain soft step (soft_method.h):
//  - the spring: its stiffness is m_eff omega^2 with m_eff about the light
//    body's mass, while its load is the heavy body's weight, so a 20 kg box
//    on a 0.02 kg one pressed the light box's springs 5.2 mm deep (and 59 mm
//    at 1:1000) where equal masses rest 0.1 mm deep;
//  - the sweeps: one Gauss-Seidel pass moves the heavy body's share of the
//    error by about m_light / m_heavy (Erleben, "Velocity-based shock
//    propagation", 2007), so four passes a step leave it sliding (24 mm in
//    2 s at 1:100).
// So in each component of dynamic bodies joined by contacts whose heaviest
// body is at least `mass_ratio` times its lightest, every point's spring
// takes its stiffness from the component's heaviest mass m_load
// (LoadedSoftness: it gives as a row of m_load would, and pushes out at the
// same rate), and after each solve and relax pass the component's normal
// rows and sticking friction rows are solved exactly, with the springs'
// compliances, by the subspace solve (subspace_solve.h; Silcowitz, Niebe and
// Erleben 2010). Worlds without such a component are untouched bit for bit.
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/mass_ratio_select.h"
#include "service/contact/soft/soft_contact.h"
#include "service/contact/subspace_solve.h"

namespace contactsim {

// Point p's three rows (normal, t1, t2) for the subspace solve, between
// solver bodies a and b, aiming at what `pass` aims at; its friction rows'
// normal is rows[normal_row] of the caller's list.
void SoftPointRows(const SoftPass& pass, const SoftPoint& p, const std::vector<SoftBody>& bodies, int a, int b,
                   int normal_row, ConstraintRow rows[3]);
// The rows' impulses back into p. Friction that slides here is held at
// +-mu lambda_n per tangent (the subspace solve's bounds) until the next
// pass sweeps it onto the disk. Projecting it onto the disk here instead
// kicked the light body between two heavy ones by the difference: a
// 0.02 kg box between two 20 kg boxes was squeezed out and the top box
// fell 100 mm.
void ReadSoftPointRows(const ConstraintRow rows[3], SoftPoint& p);

class SoftRatioSolve {
 public:
  // Finds the components of `points` that reach `options.mass_ratio` (from
  // the points' bodies only; their rows may come later: soft_contact.h).
  void Select(const SubspaceOptions& options, const std::vector<SoftBody>& bodies,
              const std::vector<SoftPoint>& points);
  // Stiffens the selected points' springs (after PrepareSoftPoints set them, SoftSprings; reads
  // their normal rows' masses). `bodies` at the step's start give the
  // masses and the inverse inertias of the solve.
  void Stiffen(const std::vector<SoftBody>& bodies, std::vector<SoftPoint>& points);
  bool active() const { return !selected_.empty(); }
  // The selected points (indices into Prepare's `points`), ascending.
  const std::vector<int>& selected() const { return selected_; }
  // After a pass: the selected points' rows solved exactly for the same
  // targets the pass aimed at (SoftNormalTarget).
  void Solve(const SoftPass& pass, std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies);

 private:
  void BuildRows(const SoftPass& pass, const std::vector<SoftPoint>& points, const std::vector<SoftBody>& bodies);
  void WriteBack(std::vector<SoftPoint>& points, std::vector<SoftBody>& bodies) const;

  SubspaceOptions options_;
  std::vector<int> selected_;       // point indices, ascending
  std::vector<double> load_mass_;   // per world body: heaviest mass of its component
  RatioSolveBodies slots_;
  std::vector<ConstraintRow> rows_;  // per selected point: normal, t1, t2
  SubspaceSolver subspace_;
};

}  // namespace contactsim
