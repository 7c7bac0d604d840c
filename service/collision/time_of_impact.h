// Time of impact: the first time in a step at which a pair's signed distance
// comes down to a target, for methods that need collision time (impulses
// with backtracking, Witkin and Baraff 1997, "Physically Based Modeling",
// collision detection notes).
//
// The caller supplies the signed distance as a function of absolute time,
// e.g. the narrowphase evaluated at poses advanced by t, so this file knows
// nothing about shapes. Two stages:
//   1. bracket: with a bound v on the closing speed, conservative
//      advancement (Mirtich 1996 thesis, "Impulse-based dynamic simulation of
//      rigid body systems", ch. 2) walks from t0 in steps of
//      (d(t) - target) / v, over which the distance cannot reach the target,
//      so no contact is stepped over (no tunnelling through thin bodies). It
//      converges linearly, with ratio 1 - (true closing speed) / v: a tight
//      bound takes one or two steps, a bound 10x too large about 80. Without
//      a bound only the end of the step is checked (classic backtracking),
//      which finds a root, not necessarily the first.
//   2. refine the bracket [a, b], d(a) > target > d(b), by bisection or by
//      regula falsi in its Illinois variant (Dowell and Jarratt 1971), which
//      halves the retained end's value when the same end is kept twice, so
//      convergence stays superlinear where plain false position stalls.
#pragma once

#include <functional>
#include <string>

#include "service/physics/status.h"

namespace contactsim {

enum class RootFinder { kBisection, kRegulaFalsi };

// "bisection" or "regula_falsi".
const char* RootFinderName(RootFinder finder);
Status ParseRootFinder(const std::string& name, RootFinder* out);

struct TimeOfImpactOptions {
  RootFinder finder = RootFinder::kRegulaFalsi;
  double target = 0.0;             // m, the distance that counts as impact (0: touching)
  double tolerance = 1e-4;         // m, accept t once |d(t) - target| <= tolerance; > 0
  int max_iterations = 100;        // per stage (advancement steps, refinement iterations); > 0
  // m/s, an upper bound on -d'(t) over the step, e.g. |v_a - v_b| +
  // |w_a| r_a + |w_b| r_b with r the bodies' bounding radii. 0: unknown,
  // so only t0 + dt is checked and thin bodies may be tunnelled through.
  double max_closing_speed = 0.0;
};

// Names the field and value of the first bad option.
Status ValidateTimeOfImpactOptions(const TimeOfImpactOptions& options);

struct TimeOfImpactResult {
  bool hit = false;        // the distance reached the target within [t0, t0 + dt]
  bool converged = true;   // false when a stage ran out of iterations (time is then the
                           // last safe time: d(time) > target)
  double time = 0.0;       // s, absolute: the time of impact, or t0 + dt without a hit
  double distance = 0.0;   // m, d(time)
  int advancement_steps = 0;  // conservative advancement steps (stage 1)
  int iterations = 0;         // root-finder iterations (stage 2)
  int evaluations = 0;        // calls of the distance function in all
};

// Signed distance (m) at absolute time t (s); negative when overlapping.
using DistanceFunction = std::function<double(double)>;

// First time in [t0, t0 + dt] where distance(t) comes within tolerance of
// target. Expects valid options and dt > 0.
TimeOfImpactResult FindTimeOfImpact(const DistanceFunction& distance, double t0, double dt,
                                    const TimeOfImpactOptions& options);

}  // namespace contactsim
