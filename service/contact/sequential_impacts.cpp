#include "service/contact/sequential_impacts.h"

#include <algorithm>
#include <cmath>

#include "service/contact/push_impulse.h"
#include "service/contact/slip_friction_step.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

// Step 1's passes over the pairs (ImpactCascade::max_passes, 20 by
// default), as the impulse method's collision_passes: a row of six touching
// bodies needs a few under e = 1 (the rows come colour by colour, so a
// strike moves two pairs a pass), and e < 1 makes the pairs meet again,
// each time e times slower, until they approach slower than the threshold.
// A phase still running after them leaves its targets at least 0 (no point
// approaches).
// Gauss-Seidel iterations over the points of one pair in one collision
// (a face's four share an impact within them).
constexpr int kPairIterations = 32;
// Step 3: passes until no impulse changes a velocity by more than
// kTolerance of the largest target, or kRestTolerance of the threshold
// where every target is about 0 (the steps after an impact, resting
// contact: below the threshold a velocity is rest), at most
// kMaxSolvePasses. A sweep over a row of n touching bodies shrinks the
// error by about cos^2(pi / n) (0.81 for 7), so ~70 passes for 1e-6 there.
// The rest tolerance is what a resting pile costs: 1,000 spheres with
// e = 0.5 took xpbd from 22 to 198 ms a step at 1% of the threshold and up
// to 500 passes, 51 ms here (docs/physics.md, "Restitution across
// simultaneous contacts").
constexpr double kTolerance = 1e-6;
constexpr double kRestTolerance = 0.1;
constexpr int kMaxSolvePasses = 100;
// within a pass, a pair's points are swept until they change by less than
// this share of the pass's tolerance (at most kPairIterations)
constexpr double kPairTolerance = 1e-3;
}  // namespace

void SequentialImpacts::Begin(int bodies) {
  for (int i : touched_) local_[i] = -1;
  local_.resize(bodies, -1);
  touched_.clear();
  start_.clear();
  rows_.clear();
}

void SequentialImpacts::SetBody(int index, const Vec3& v, const Vec3& w, double inv_mass) {
  local_[index] = static_cast<int>(start_.size());
  touched_.push_back(index);
  start_.push_back({v, w, inv_mass});
}

double SequentialImpacts::Approach(int k) const {
  const ImpactRow& r = rows_[k];
  const Velocity& A = scratch_[local_[r.a]];
  const Velocity& B = scratch_[local_[r.b]];
  return r.n.dot(B.v - A.v) + r.rb_n.dot(B.w) - r.ra_n.dot(A.w) + gain_[k];
}

void SequentialImpacts::SetGains() {
  gain_.assign(rows_.size(), 0.0);
  for (size_t k = 0; k < rows_.size(); ++k) gain_[k] = std::min(rows_[k].impact - Approach(k), 0.0);
}

void SequentialImpacts::Push(double j, const ImpactRow& r) {
  PushImpulse(j, r.n, r.ia_n, r.ib_n, scratch_[local_[r.a]], scratch_[local_[r.b]]);
}

double SequentialImpacts::Slip(int k, int axis) const {
  const ImpactTangent& t = rows_[k].t[axis];
  const Velocity& A = scratch_[local_[rows_[k].a]];
  const Velocity& B = scratch_[local_[rows_[k].b]];
  return t.d.dot(B.v - A.v) + t.rb.dot(B.w) - t.ra.dot(A.w);
}

void SequentialImpacts::SetTangentMasses() {
  tangent_.assign(rows_.size(), TangentMass());
  for (size_t k = 0; k < rows_.size(); ++k) {
    const ImpactRow& r = rows_[k];
    if (r.friction <= 0.0) continue;
    const double linear = start_[local_[r.a]].inv_mass + start_[local_[r.b]].inv_mass;
    const auto K = [&](const ImpactTangent& x, const ImpactTangent& y, double lin) {
      return lin + x.ra.dot(y.ia) + x.rb.dot(y.ib);
    };
    const double k11 = K(r.t[0], r.t[0], linear), k22 = K(r.t[1], r.t[1], linear);
    tangent_[k] = {k11 > 0.0 ? 1.0 / k11 : 0.0, k22 > 0.0 ? 1.0 / k22 : 0.0, K(r.t[0], r.t[1], 0.0)};
  }
}

double SequentialImpacts::CollideFriction(int k) {
  const ImpactRow& r = rows_[k];
  const TangentMass& m = tangent_[k];
  double l1 = jt_[2 * k], l2 = jt_[2 * k + 1];
  SlipFrictionStep(r.friction * j_[k], Slip(k, 0), Slip(k, 1), m.m1, m.m2, m.k12, &l1, &l2);
  const double d1 = l1 - jt_[2 * k], d2 = l2 - jt_[2 * k + 1];
  jt_[2 * k] = l1, jt_[2 * k + 1] = l2;
  Velocity& A = scratch_[local_[r.a]];
  Velocity& B = scratch_[local_[r.b]];
  PushImpulse(d1, r.t[0].d, r.t[0].ia, r.t[0].ib, A, B);
  PushImpulse(d2, r.t[1].d, r.t[1].ia, r.t[1].ib, A, B);
  return std::max(m.m1 > 0.0 ? std::abs(d1) / m.m1 : 0.0, m.m2 > 0.0 ? std::abs(d2) / m.m2 : 0.0);
}

bool SequentialImpacts::Collide(int begin, int end, double threshold) {
  bool hit = false;
  for (int k = begin; k < end && !hit; ++k) hit = Approach(k) < -threshold;
  if (!hit) return false;
  // Newton's law where a point approached, no approach elsewhere (a
  // separating point held to its speed would be pushed whenever another
  // point's impulse slowed it: impulse_method.cpp)
  double scale = 0.0;  // m/s, the fastest approach
  for (int k = begin; k < end; ++k) {
    const double u = Approach(k);
    rows_[k].target = u < -threshold ? -rows_[k].restitution * u : 0.0;
    j_[k] = 0.0;
    jt_[2 * k] = jt_[2 * k + 1] = 0.0;
    scale = std::max(scale, -u);
  }
  for (int it = 0; it < kPairIterations; ++it) {
    double worst = 0.0;
    for (int k = begin; k < end; ++k) {
      ImpactRow& r = rows_[k];
      const double next = std::max(0.0, j_[k] + (r.target - Approach(k)) * r.mass_n);
      const double d = next - j_[k];
      j_[k] = next;
      Push(d, r);
      worst = std::max(worst, std::abs(d) / r.mass_n);
      // Coulomb friction within the cone of the collision's normal impulse
      // (Guendelman, Bridson and Fedkiw 2003, the collision phase)
      if (r.friction > 0.0) worst = std::max(worst, CollideFriction(k));
    }
    if (worst <= kTolerance * scale) break;
  }
  for (int k = begin; k < end; ++k) {
    rows_[k].phase += j_[k];
    rows_[k].t[0].phase += jt_[2 * k];
    rows_[k].t[1].phase += jt_[2 * k + 1];
  }
  return true;
}

void SequentialImpacts::KeepTakingPartComponents() {
  UnionFind sets(static_cast<int>(start_.size()));
  for (const ImpactRow& r : rows_) {
    if (start_[local_[r.a]].inv_mass > 0.0 && start_[local_[r.b]].inv_mass > 0.0) {
      sets.Join(local_[r.a], local_[r.b]);
    }
  }
  // a component is named by the root of either dynamic body of its rows
  auto root = [&](const ImpactRow& r) {
    return sets.Root(start_[local_[r.a]].inv_mass > 0.0 ? local_[r.a] : local_[r.b]);
  };
  // a struck row with friction makes its component take part only where no
  // static or kinematic body holds it (ImpactRow::struck)
  std::vector<char> held(start_.size(), 0);
  for (const ImpactRow& r : rows_) {
    if (start_[local_[r.a]].inv_mass <= 0.0 || start_[local_[r.b]].inv_mass <= 0.0) held[root(r)] = 1;
  }
  std::vector<char> taking_part(start_.size(), 0);
  for (const ImpactRow& r : rows_) {
    const int c = root(r);
    if (r.restitution > 0.0 || (r.struck && (r.friction <= 0.0 || !held[c]))) taking_part[c] = 1;
  }
  size_t kept = 0;
  for (size_t k = 0; k < rows_.size(); ++k) {
    if (!taking_part[root(rows_[k])]) continue;
    rows_[kept] = rows_[k];
    gain_[kept++] = gain_[k];
  }
  rows_.resize(kept);
  gain_.resize(kept);
}

bool SequentialImpacts::FindTargets(double threshold, const ImpactCascade& cascade) {
  threshold_ = threshold;
  scratch_ = start_;
  gain_.assign(rows_.size(), 0.0);
  SetGains();
  KeepTakingPartComponents();
  if (rows_.empty()) return false;
  j_.assign(rows_.size(), 0.0);
  jt_.assign(2 * rows_.size(), 0.0);
  SetTangentMasses();
  double fastest = 0.0;  // m/s
  for (size_t k = 0; k < rows_.size(); ++k) fastest = std::max(fastest, -Approach(static_cast<int>(k)));
  for (int pass = 0; pass < cascade.max_passes; ++pass) {
    if (pass == 1 && cascade.relative > 0.0) threshold = std::min(threshold, cascade.relative * fastest);
    bool any = false;
    for (int begin = 0; begin < static_cast<int>(rows_.size());) {
      int end = begin + 1;
      while (end < static_cast<int>(rows_.size()) && rows_[end].group == rows_[begin].group) ++end;
      any = Collide(begin, end, threshold) || any;
      begin = end;
    }
    if (!any) break;
  }
  for (size_t k = 0; k < rows_.size(); ++k) rows_[k].target = std::max(Approach(k), 0.0);
  return true;
}

namespace {

double SlipOf(const ImpactTangent& t, const SoftBody& A, const SoftBody& B) {
  return t.d.dot(B.v - A.v) + t.rb.dot(B.w) - t.ra.dot(A.w) - t.held;
}

}  // namespace

double SequentialImpacts::SolveRow(int k, std::vector<SoftBody>& bodies) {
  ImpactRow& r = rows_[k];
  SoftBody& A = bodies[r.a];
  SoftBody& B = bodies[r.b];
  const double vn = r.n.dot(B.v - A.v) + r.rb_n.dot(B.w) - r.ra_n.dot(A.w);
  const double next = std::max(0.0, r.lambda + (r.target - vn) * r.mass_n);
  const double d = next - r.lambda;
  r.lambda = next;
  PushImpulse(d, r.n, r.ia_n, r.ib_n, A, B);
  double change = std::abs(d) / r.mass_n;
  if (r.friction <= 0.0) return change;
  // the slip the method's solve left, held within the cone of what this
  // solve changed the normal impulse by (the method's friction used the
  // cone of its own)
  const TangentMass& m = tangent_[k];
  double l1 = r.t[0].lambda, l2 = r.t[1].lambda;
  const double limit = r.friction * std::abs(r.lambda - method_lambda_[k]);
  SlipFrictionStep(limit, SlipOf(r.t[0], A, B), SlipOf(r.t[1], A, B), m.m1, m.m2, m.k12, &l1, &l2);
  const double d1 = l1 - r.t[0].lambda, d2 = l2 - r.t[1].lambda;
  r.t[0].lambda = l1, r.t[1].lambda = l2;
  PushImpulse(d1, r.t[0].d, r.t[0].ia, r.t[0].ib, A, B);
  PushImpulse(d2, r.t[1].d, r.t[1].ia, r.t[1].ib, A, B);
  if (m.m1 > 0.0) change = std::max(change, std::abs(d1) / m.m1);
  if (m.m2 > 0.0) change = std::max(change, std::abs(d2) / m.m2);
  return change;
}

void SequentialImpacts::Solve(std::vector<SoftBody>& bodies) {
  double largest = 0.0;
  for (const ImpactRow& r : rows_) largest = std::max(largest, r.target);
  const double tolerance = std::max(kTolerance * largest, kRestTolerance * threshold_);
  const int count = static_cast<int>(rows_.size());
  method_lambda_.resize(rows_.size());
  for (int k = 0; k < count; ++k) {
    ImpactRow& r = rows_[k];
    method_lambda_[k] = r.lambda;
    if (r.friction <= 0.0) continue;
    for (ImpactTangent& t : r.t) {
      t.lambda = 0.0;
      t.held = 0.0;
      t.held = SlipOf(t, bodies[r.a], bodies[r.b]);
    }
  }
  for (int pass = 0; pass < kMaxSolvePasses; ++pass) {
    double worst = 0.0;
    // a pair's points until they agree: a face's four corners are
    // dependent, and a sweep stopped short of them leaves the face's share
    // uneven, which turned a box landing flat at 1e-3 rad/s
    for (int begin = 0; begin < count;) {
      int end = begin + 1;
      while (end < count && rows_[end].group == rows_[begin].group) ++end;
      for (int it = 0; it < kPairIterations; ++it) {
        double change = 0.0;
        for (int k = begin; k < end; ++k) change = std::max(change, SolveRow(k, bodies));
        if (it == 0) worst = std::max(worst, change);
        if (end - begin == 1 || change <= kPairTolerance * tolerance) break;
      }
      begin = end;
    }
    if (worst <= tolerance) break;
  }
}

}  // namespace contactsim
