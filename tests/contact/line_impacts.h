// The analytic outcome of a body striking a row of equal bodies on a line
// (frictionless, no gravity), with Newton's impact law on each pair that
// meets, v+ = -e v- (Hahn 1988; Mirtich 1996), collisions taken one at a
// time in the order they happen: the event-driven answer the sequential
// impulses of Guendelman, Bridson and Fedkiw 2003 approach.
//
// The bodies start `gap` apart, the first at v0, the others at rest. For
// equal masses a pair's impact changes only its two velocities:
//   u = v_b - v_a < 0,  v_a += (1 + e) u / 2,  v_b -= (1 + e) u / 2,
// which keeps the momentum and leaves them at u+ = -e u. The next event is
// the pair that closes its gap first. Times and distances scale together
// with the gap, so equal gaps give the same velocities at any size: a row of
// touching bodies (gap 0) is answered as the limit of vanishing equal gaps.
// With e = 1 this is Newton's cradle (the last leaves at v0, the others
// rest); with e = 0 every pair ends together at v0 / n.
#pragma once

#include <limits>
#include <vector>

namespace contactsim {
namespace testing {

// Final velocities (m/s along the line) of `bodies` equal bodies, the first
// struck into the others at v0 > 0.
inline std::vector<double> StruckLineVelocities(int bodies, double v0, double e) {
  std::vector<double> v(bodies, 0.0), gap(bodies - 1, 1.0);  // any equal gaps (above)
  v[0] = v0;
  // an approach slower than this is at rest: e < 1 on touching bodies
  // would otherwise collide again without end, each time e times slower
  const double settled = 1e-12 * v0;
  for (int event = 0; event < 1000000; ++event) {
    int next = -1;
    double soonest = std::numeric_limits<double>::infinity();
    for (int k = 0; k + 1 < bodies; ++k) {
      const double closing = v[k] - v[k + 1];
      if (closing <= settled) continue;
      const double t = gap[k] / closing;
      if (t < soonest) soonest = t, next = k;
    }
    if (next < 0) break;
    for (int k = 0; k + 1 < bodies; ++k) gap[k] += (v[k + 1] - v[k]) * soonest;
    gap[next] = 0.0;
    const double u = v[next + 1] - v[next];
    v[next] += 0.5 * (1.0 + e) * u;
    v[next + 1] -= 0.5 * (1.0 + e) * u;
  }
  return v;
}

}  // namespace testing
}  // namespace contactsim
