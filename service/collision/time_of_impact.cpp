#include "service/collision/time_of_impact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace contactsim {
namespace {

// Relative width under which a bracket cannot shrink further in doubles: the
// distance jumps across it, so the time is resolved as well as it can be.
constexpr double kMinRelativeInterval = 4.0 * std::numeric_limits<double>::epsilon();

// Stage 2: shrinks [a, b] with f(a) > tol and f(b) < -tol, f = d - target.
void Refine(const std::function<double(double)>& f, double a, double fa, double b, double fb,
            const TimeOfImpactOptions& options, TimeOfImpactResult* result) {
  const double tol = options.tolerance;
  const bool illinois = options.finder == RootFinder::kRegulaFalsi;
  // which end the last iteration moved: +1 for a, -1 for b, 0 none yet
  int last_moved = 0;
  // the values used for the secant; Illinois halves the one kept twice
  double secant_fa = fa, secant_fb = fb;
  result->hit = true;
  while (true) {
    if (b - a <= kMinRelativeInterval * std::max(std::abs(a), std::abs(b))) {
      result->time = a;
      result->distance = fa + options.target;
      return;
    }
    if (result->iterations >= options.max_iterations) {
      result->converged = false;
      result->time = a;
      result->distance = fa + options.target;
      return;
    }
    ++result->iterations;
    double m = 0.5 * (a + b);
    if (illinois) {
      // root of the secant through (a, fa) and (b, fb)
      const double secant = (a * secant_fb - b * secant_fa) / (secant_fb - secant_fa);
      if (secant > a && secant < b) m = secant;
    }
    const double fm = f(m);
    if (std::abs(fm) <= tol) {
      result->time = m;
      result->distance = fm + options.target;
      return;
    }
    if (fm > 0.0) {
      a = m;
      fa = secant_fa = fm;
      if (last_moved == 1) secant_fb *= 0.5;
      last_moved = 1;
    } else {
      b = m;
      fb = secant_fb = fm;
      if (last_moved == -1) secant_fa *= 0.5;
      last_moved = -1;
    }
  }
}

}  // namespace

const char* RootFinderName(RootFinder finder) {
  return finder == RootFinder::kBisection ? "bisection" : "regula_falsi";
}

Status ParseRootFinder(const std::string& name, RootFinder* out) {
  if (name == "bisection") {
    *out = RootFinder::kBisection;
  } else if (name == "regula_falsi") {
    *out = RootFinder::kRegulaFalsi;
  } else {
    return Status::InvalidArgument("unknown root finder \"" + name + "\"; known: bisection, regula_falsi");
  }
  return Status::Ok();
}

Status ValidateTimeOfImpactOptions(const TimeOfImpactOptions& options) {
  std::ostringstream msg;
  if (!std::isfinite(options.target)) {
    msg << "time of impact target must be finite, got " << options.target;
  } else if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance)) {
    msg << "time of impact tolerance must be positive and finite, got " << options.tolerance;
  } else if (options.max_iterations <= 0) {
    msg << "time of impact max_iterations must be positive, got " << options.max_iterations;
  } else if (!(options.max_closing_speed >= 0.0) || !std::isfinite(options.max_closing_speed)) {
    msg << "time of impact max_closing_speed must be >= 0 and finite, got " << options.max_closing_speed;
  } else {
    return Status::Ok();
  }
  return Status::InvalidArgument(msg.str());
}

TimeOfImpactResult FindTimeOfImpact(const DistanceFunction& distance, double t0, double dt,
                                    const TimeOfImpactOptions& options) {
  TimeOfImpactResult result;
  // f = d - target, counted
  const std::function<double(double)> f = [&](double t) {
    ++result.evaluations;
    return distance(t) - options.target;
  };
  const double tol = options.tolerance;
  const double t1 = t0 + dt;
  auto finish = [&](bool hit, double t, double ft) {
    result.hit = hit;
    result.time = t;
    result.distance = ft + options.target;
    return result;
  };

  double a = t0;
  double fa = f(a);
  if (fa <= tol) return finish(true, a, fa);  // touching or overlapping already

  if (options.max_closing_speed <= 0.0) {
    // classic backtracking: the end of the step decides
    const double fb = f(t1);
    if (fb > tol) return finish(false, t1, fb);
    if (fb >= -tol) return finish(true, t1, fb);
    Refine(f, a, fa, t1, fb, options, &result);
    return result;
  }

  // stage 1, conservative advancement: d(t) >= d(a) - v (t - a), so over a
  // step of f(a) / v the distance stays above the target; each step is at
  // least tol / v long since f(a) > tol
  while (true) {
    if (result.advancement_steps >= options.max_iterations) {
      result.converged = false;
      return finish(false, a, fa);
    }
    ++result.advancement_steps;
    const double t = std::min(t1, a + fa / options.max_closing_speed);
    const double ft = f(t);
    if (std::abs(ft) <= tol) return finish(true, t, ft);
    if (ft < -tol) {
      // the speed bound was not a bound; the bracket still holds a root
      Refine(f, a, fa, t, ft, options, &result);
      return result;
    }
    if (t >= t1) return finish(false, t1, ft);
    a = t;
    fa = ft;
  }
}

}  // namespace contactsim
