#include "service/contact/penalty/penalty_damping_bound.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

// power iterations for lambda_max(B), p > 2; B is a few points across, and
// a face's modes are apart enough that 16 products settle it to a few parts
// in 1e3 (from below: kMaxShare keeps room to 2 for the rest)
constexpr int kPowerIterations = 16;

// m v by its entries: Eigen's 3 x 3 product here, one more caller of the
// template the sub-steps' lever arms use, made GCC stop inlining it there
// (2.4% more instructions a pyramid step)
Vec3 Times(const Mat3& m, const Vec3& v) {
  return Vec3(m(0, 0) * v.x() + m(0, 1) * v.y() + m(0, 2) * v.z(), m(1, 0) * v.x() + m(1, 1) * v.y() + m(1, 2) * v.z(),
              m(2, 0) * v.x() + m(2, 1) * v.y() + m(2, 2) * v.z());
}

}  // namespace

void PenaltyDampingBound::Prepare(const World& world, const std::vector<PenaltyRow>& rows, double h, bool linear) {
  bounds_.clear();
  if (!linear) return;
  const auto& bodies = world.bodies();
  int pairs = 0;
  for (const PenaltyRow& row : rows) {
    if (row.engaged) pairs = std::max(pairs, row.pair + 1);
  }
  // the rows of each pair, by counting; the pairs with two points touching
  // at the step's start; each dynamic body's n_b then (as stage 2 counts it)
  start_.assign(pairs + 2, 0);
  touching_.assign(pairs, 0);
  shared_.assign(bodies.size(), 0.0);
  bool several = false;
  for (const PenaltyRow& row : rows) {
    if (!row.engaged) continue;
    ++start_[row.pair + 2];
    if (!(row.depth > row.anchor.rest_depth)) continue;
    several = several || ++touching_[row.pair] > 1;
    if (bodies[row.a].IsDynamic()) shared_[row.a] += 1.0 / row.nc;
    if (bodies[row.b].IsDynamic()) shared_[row.b] += 1.0 / row.nc;
  }
  if (!several) return;
  for (int q = 0; q < pairs; ++q) start_[q + 2] += start_[q + 1];
  order_.resize(start_[pairs + 1]);
  for (size_t k = 0; k < rows.size(); ++k) {
    if (rows[k].engaged) order_[start_[rows[k].pair + 1]++] = static_cast<int>(k);
  }
  bounds_.assign(rows.size(), Bound());
  inv_inertia_.resize(bodies.size());
  inertia_set_.assign(bodies.size(), 0);
  for (int q = 0; q < pairs; ++q) {
    if (touching_[q] < 2) continue;
    const int* points = &order_[start_[q]];
    const int p = start_[q + 1] - start_[q];
    const PenaltyRow& first = rows[points[0]];
    const double shared = std::max(1.0, std::max(shared_[first.a], shared_[first.b]));
    const Bound bound = PairBound(world, rows, points, p, h, shared);
    if (bound.share <= kMaxShare) continue;
    for (int i = 0; i < p; ++i) bounds_[points[i]] = bound;
  }
}

double PenaltyDampingBound::BoundedScale(size_t k, double shared) const {
  // B(n_b) = D B(1) D with D^2 = diag((1 + a_i) / (1 + n_b a_i)), largest
  // at the least a_i
  const double a = bounds_[k].least;
  const double share = bounds_[k].share * (1.0 + a) / (1.0 + shared * a);
  return share > kMaxShare ? kMaxShare / share : 1.0;
}

const Mat3& PenaltyDampingBound::InvInertia(const World& world, int body) {
  if (!inertia_set_[body]) {
    const RigidBody& b = world.bodies()[body];
    inv_inertia_[body] = b.IsDynamic() ? b.InvInertiaWorld() : Mat3::Zero();
    inertia_set_[body] = 1;
  }
  return inv_inertia_[body];
}

// a_i = h c_i K_ii, and B(n)_ij = sqrt(w_i w_j) K_ij with
// w_i = h c_i / (1 + n a_i)
PenaltyDampingBound::Bound PenaltyDampingBound::PairBound(const World& world, const std::vector<PenaltyRow>& rows,
                                                          const int* points, int p, double h, double shared) {
  Bound bound;
  // trace(B(n_b)) bounds lambda_max from above (B is positive
  // semi-definite): a pair of saturated points under a busy body ends here
  a_.resize(p);
  double trace = 0.0;
  for (int i = 0; i < p; ++i) {
    const PenaltyRow& row = rows[points[i]];
    a_[i] = h * row.damping / row.nc * row.inv_mass_n;
    trace += a_[i] / (1.0 + shared * a_[i]);
  }
  if (trace <= kMaxShare) return bound;
  const auto& bodies = world.bodies();
  const PenaltyRow& first = rows[points[0]];
  const int lo = std::min(first.a, first.b), hi = std::max(first.a, first.b);
  const RigidBody& L = bodies[lo];
  const RigidBody& H = bodies[hi];
  const double inv_mass = (L.IsDynamic() ? L.inv_mass : 0.0) + (H.IsDynamic() ? H.inv_mass : 0.0);
  const Mat3& il = InvInertia(world, lo);
  const Mat3& ih = InvInertia(world, hi);
  points_.resize(p);
  for (int i = 0; i < p; ++i) {
    const PenaltyRow& row = rows[points[i]];
    const bool forward = row.a == lo;
    Point& q = points_[i];
    q.n = forward ? row.n : Vec3(-row.n);
    q.jl = (forward ? row.ra : row.rb).cross(q.n);
    q.jh = (forward ? row.rb : row.ra).cross(q.n);
    q.kl = Times(il, q.jl);
    q.kh = Times(ih, q.jh);
  }
  // K_ij scaled to B(n_b); Gershgorin's row sums bound lambda_max from above
  k_.resize(p * p);
  w_.resize(p);
  for (int i = 0; i < p; ++i) w_[i] = 1.0 / (1.0 + shared * a_[i]);
  double gershgorin = 0.0;
  for (int i = 0; i < p; ++i) {
    const PenaltyRow& row = rows[points[i]];
    const Point& qi = points_[i];
    double sum = 0.0;
    for (int j = 0; j < p; ++j) {
      const Point& qj = points_[j];
      const double kij = inv_mass * qi.n.dot(qj.n) + qi.jl.dot(qj.kl) + qi.jh.dot(qj.kh);
      k_[i * p + j] = kij;
      const PenaltyRow& other = rows[points[j]];
      sum += std::abs(kij) * h * std::sqrt(row.damping / row.nc * w_[i] * other.damping / other.nc * w_[j]);
    }
    gershgorin = std::max(gershgorin, sum);
  }
  if (gershgorin <= kMaxShare) return bound;
  // lambda_max(B(1)), stored with the least a_i for Scale
  b_.resize(p * p);
  for (int i = 0; i < p; ++i) w_[i] = h * rows[points[i]].damping / rows[points[i]].nc / (1.0 + a_[i]);
  bound.least = a_[0];
  for (int i = 0; i < p; ++i) {
    bound.least = std::min(bound.least, a_[i]);
    for (int j = 0; j < p; ++j) b_[i * p + j] = std::sqrt(w_[i] * w_[j]) * k_[i * p + j];
  }
  bound.share = LargestEigenvalue(p);
  return bound;
}

// lambda_max of the symmetric positive semi-definite b_ (p x p): exact for
// p = 2, else power iteration from a start with a part along every mode
double PenaltyDampingBound::LargestEigenvalue(int p) {
  if (p == 2) {
    const double mean = 0.5 * (b_[0] + b_[3]), half = 0.5 * (b_[0] - b_[3]);
    return mean + std::sqrt(half * half + b_[1] * b_[1]);
  }
  u_.resize(2 * p);
  double* u = u_.data();
  double* v = u_.data() + p;
  for (int i = 0; i < p; ++i) u[i] = 1.0 + 0.37 * i;
  double lambda = 0.0;
  for (int it = 0; it < kPowerIterations; ++it) {
    double uu = 0.0, uv = 0.0, vv = 0.0;
    for (int i = 0; i < p; ++i) {
      double s = 0.0;
      for (int j = 0; j < p; ++j) s += b_[i * p + j] * u[j];
      v[i] = s;
      uu += u[i] * u[i];
      uv += u[i] * s;
      vv += s * s;
    }
    lambda = uv / uu;
    const double norm = 1.0 / std::sqrt(std::max(vv, 1e-300));
    for (int i = 0; i < p; ++i) u[i] = v[i] * norm;
  }
  return lambda;
}

}  // namespace contactsim
