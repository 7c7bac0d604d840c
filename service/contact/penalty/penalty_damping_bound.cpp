#include "service/contact/penalty/penalty_damping_bound.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

// power iterations for lambda_max(B), p > 2; B is at most a few points
// across, and a face's modes are apart enough that 16 products settle it to
// a few parts in 1e3 (from below: kMaxShare keeps room to 2 for the rest)
constexpr int kPowerIterations = 16;

}  // namespace

void PenaltyDampingBound::Prepare(const World& world, const std::vector<PenaltyRow>& rows, double h, bool linear) {
  scale_.clear();
  if (!linear) return;
  int pairs = 0;
  for (const PenaltyRow& row : rows) {
    if (row.engaged) pairs = std::max(pairs, row.pair + 1);
  }
  // the rows of each pair, by counting
  start_.assign(pairs + 2, 0);
  for (const PenaltyRow& row : rows) {
    if (row.engaged) ++start_[row.pair + 2];
  }
  bool several = false;
  for (int q = 0; q < pairs; ++q) several = several || start_[q + 2] > 1;
  if (!several) return;
  for (int q = 0; q < pairs; ++q) start_[q + 2] += start_[q + 1];
  order_.resize(start_[pairs + 1]);
  for (size_t k = 0; k < rows.size(); ++k) {
    if (rows[k].engaged) order_[start_[rows[k].pair + 1]++] = static_cast<int>(k);
  }
  scale_.assign(rows.size(), 1.0);
  for (int q = 0; q < pairs; ++q) {
    const int p = start_[q + 1] - start_[q];
    if (p < 2) continue;
    const double share = LargestShare(world, rows, &order_[start_[q]], p, h);
    if (share <= kMaxShare) continue;
    for (int i = 0; i < p; ++i) scale_[order_[start_[q] + i]] = kMaxShare / share;
  }
}

double PenaltyDampingBound::LargestShare(const World& world, const std::vector<PenaltyRow>& rows, const int* points,
                                         int p, double h) {
  const auto& bodies = world.bodies();
  const PenaltyRow& first = rows[points[0]];
  const int lo = std::min(first.a, first.b), hi = std::max(first.a, first.b);
  const RigidBody& L = bodies[lo];
  const RigidBody& H = bodies[hi];
  const double inv_mass = (L.IsDynamic() ? L.inv_mass : 0.0) + (H.IsDynamic() ? H.inv_mass : 0.0);
  const Mat3 il = L.IsDynamic() ? L.InvInertiaWorld() : Mat3::Zero();
  const Mat3 ih = H.IsDynamic() ? H.InvInertiaWorld() : Mat3::Zero();
  // per point: the normal from lo to hi, and the angular parts of J and of
  // M^-1 J^T on each body
  const int count = p;
  points_.resize(count);
  for (int i = 0; i < count; ++i) {
    const PenaltyRow& row = rows[points[i]];
    const bool forward = row.a == lo;
    Point& q = points_[i];
    q.n = forward ? row.n : Vec3(-row.n);
    q.jl = (forward ? row.ra : row.rb).cross(q.n);
    q.jh = (forward ? row.rb : row.ra).cross(q.n);
    q.kl = il * q.jl;
    q.kh = ih * q.jh;
  }
  b_.assign(count * count, 0.0);
  w_.resize(count);
  for (int i = 0; i < count; ++i) {
    const PenaltyRow& row = rows[points[i]];
    const Point& q = points_[i];
    const double kii = inv_mass + q.jl.dot(q.kl) + q.jh.dot(q.kh);
    const double c = row.damping / row.nc;
    // h c' with n_b = 1 (stage 2's cut), times K_ii below
    w_[i] = h * c / (1.0 + h * c * kii);
    b_[i * count + i] = w_[i] * kii;
  }
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < i; ++j) {
      const Point& qi = points_[i];
      const Point& qj = points_[j];
      const double kij = inv_mass * qi.n.dot(qj.n) + qi.jl.dot(qj.kl) + qi.jh.dot(qj.kh);
      b_[i * count + j] = b_[j * count + i] = std::sqrt(w_[i] * w_[j]) * kij;
    }
  }
  // Gershgorin first: most pairs end here
  double gershgorin = 0.0;
  for (int i = 0; i < count; ++i) {
    double sum = 0.0;
    for (int j = 0; j < count; ++j) sum += std::abs(b_[i * count + j]);
    gershgorin = std::max(gershgorin, sum);
  }
  if (gershgorin <= kMaxShare) return gershgorin;
  if (count == 2) {
    const double mean = 0.5 * (b_[0] + b_[3]), half = 0.5 * (b_[0] - b_[3]);
    return mean + std::sqrt(half * half + b_[1] * b_[1]);
  }
  u_.resize(2 * count);
  double* u = u_.data();
  double* v = u_.data() + count;
  for (int i = 0; i < count; ++i) u[i] = 1.0 + 0.37 * i;  // a part along every mode
  double lambda = 0.0;
  for (int it = 0; it < kPowerIterations; ++it) {
    double uu = 0.0, uv = 0.0;
    for (int i = 0; i < count; ++i) {
      double s = 0.0;
      for (int j = 0; j < count; ++j) s += b_[i * count + j] * u[j];
      v[i] = s;
      uu += u[i] * u[i];
      uv += u[i] * s;
    }
    lambda = uv / uu;
    double vv = 0.0;
    for (int i = 0; i < count; ++i) vv += v[i] * v[i];
    const double norm = 1.0 / std::sqrt(std::max(vv, 1e-300));
    for (int i = 0; i < count; ++i) u[i] = v[i] * norm;
  }
  return lambda;
}

}  // namespace contactsim
