#include "service/contact/penalty/penalty_preload.h"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>

#include "service/contact/union_find.h"
#include "service/physics/portable_math.h"

namespace contactsim {
namespace {

// m: a row whose spring depth is above -kTouching touches (step 1): a
// placement exactly touching carries round-off of the positions, far below
// this, and a gap of a micrometre is still closed by g within the step
// (g dt^2 = 0.17 mm at 240 Hz) before a spring would bite.
constexpr double kTouching = 1e-6;
// step 2: passes until no force changes a row's acceleration by more than
// kTolerance of the largest. Gauss-Seidel spreads a load down a chain of
// bodies a body a pass and settles a face's four corners slowly: a stack
// of 20 cubes on their corners takes about 2,200 passes, the 20-course
// pyramid of box_pyramid.pbtxt about 1,000 (once, when it is placed: 0.32e9
// instructions, six of its steps). Stopped at 500, the stack's uneven
// corner loads walked it 1.2 mm sideways in 10 s.
constexpr double kTolerance = 1e-6;
constexpr int kMaxPasses = 5000;

bool Touching(const PenaltyRow& row) { return row.engaged && row.depth - row.anchor.rest_depth > -kTouching; }

}  // namespace

void PenaltyPreload::SpreadOverPairs(const std::vector<PenaltyRow>& rows) {
  int pairs = 0;
  for (const Row& r : rows_) pairs = std::max(pairs, rows[r.row].pair + 1);
  first_.assign(pairs, -1);
  next_.assign(rows_.size(), -1);
  for (int k = static_cast<int>(rows_.size()) - 1; k >= 0; --k) {
    int& head = first_[rows[rows_[k].row].pair];
    next_[k] = head;
    head = k;
  }
  for (int head : first_) {
    if (head < 0 || next_[head] < 0) continue;  // none, or one point
    // the pair's points in its tangent plane about their centroid
    const PenaltyRow& lead = rows[rows_[head].row];
    Vec3 centre = Vec3::Zero();
    double total = 0.0;
    int count = 0;
    for (int k = head; k >= 0; k = next_[k]) {
      centre += rows[rows_[k].row].ra;
      total += rows_[k].lambda;
      ++count;
    }
    centre /= count;
    // the load's moment about the centroid, and the points' second moments
    Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
    Eigen::Vector2d moment = Eigen::Vector2d::Zero();
    for (int k = head; k >= 0; k = next_[k]) {
      const Vec3 p = rows[rows_[k].row].ra - centre;
      const Eigen::Vector2d uv(p.dot(lead.t1), p.dot(lead.t2));
      second += uv * uv.transpose();
      moment += rows_[k].lambda * uv;
    }
    // loads linear over the points (equal springs of a rigid pair) with the
    // same force and moment; a line of points (a capsule) along it only
    const Eigen::Vector2d slope = second.completeOrthogonalDecomposition().solve(moment);
    bool kept = true;
    for (int k = head; k >= 0 && kept; k = next_[k]) {
      const Vec3 p = rows[rows_[k].row].ra - centre;
      kept = total / count + slope.dot(Eigen::Vector2d(p.dot(lead.t1), p.dot(lead.t2))) >= 0.0;
    }
    if (!kept) continue;  // the load's centre too near an edge: the solve's own loads
    for (int k = head; k >= 0; k = next_[k]) {
      const Vec3 p = rows[rows_[k].row].ra - centre;
      rows_[k].lambda = total / count + slope.dot(Eigen::Vector2d(p.dot(lead.t1), p.dot(lead.t2)));
    }
  }
}

double PenaltyPreload::Approach(const Row& r) const {
  return r.n.dot(acc_v_[r.b] - acc_v_[r.a]) + r.rb_n.dot(acc_w_[r.b]) - r.ra_n.dot(acc_w_[r.a]);
}

void PenaltyPreload::SolveLoads() {
  double scale = 0.0;  // m/s^2, the largest approach
  for (const Row& r : rows_) scale = std::max(scale, -Approach(r));
  if (scale <= 0.0) return;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    double worst = 0.0;
    for (Row& r : rows_) {
      const double next = std::max(0.0, r.lambda - Approach(r) * r.mass_n);
      const double d = next - r.lambda;
      r.lambda = next;
      acc_v_[r.a] -= (inv_mass_[r.a] * d) * r.n;
      acc_w_[r.a] -= d * r.ia_n;
      acc_v_[r.b] += (inv_mass_[r.b] * d) * r.n;
      acc_w_[r.b] += d * r.ib_n;
      worst = std::max(worst, std::abs(d) / r.mass_n);
    }
    if (worst <= kTolerance * scale) break;
  }
}

int PenaltyPreload::Apply(const World& world, const PenaltyParams& params, double threshold,
                          std::vector<PenaltyRow>* rows) {
  const auto& bodies = world.bodies();
  const int n = static_cast<int>(bodies.size());
  // step 1: the components, and which of them were placed at rest
  UnionFind sets(n);
  bool any = false;
  for (const PenaltyRow& row : *rows) {
    if (!Touching(row)) continue;
    any = true;
    if (bodies[row.a].IsDynamic() && bodies[row.b].IsDynamic()) sets.Join(row.a, row.b);
  }
  if (!any) return 0;
  auto root = [&](const PenaltyRow& row) { return sets.Root(bodies[row.a].IsDynamic() ? row.a : row.b); };
  std::vector<char> moved(n, 0);  // per root: a touching row was seen before, or is no rest
  for (const PenaltyRow& row : *rows) {
    if (!Touching(row)) continue;
    if (row.had_anchor || std::abs(row.vn0) > threshold) moved[root(row)] = 1;
  }
  // step 2 on the rows of the placed components
  rows_.clear();
  for (int k = 0; k < static_cast<int>(rows->size()); ++k) {
    const PenaltyRow& row = (*rows)[k];
    if (!Touching(row) || moved[root(row)] || row.inv_mass_n <= 0.0) continue;
    const RigidBody& A = bodies[row.a];
    const RigidBody& B = bodies[row.b];
    Row r;
    r.row = k;
    r.a = row.a, r.b = row.b;
    r.n = row.n;
    r.ra_n = row.ra.cross(row.n);
    r.rb_n = row.rb.cross(row.n);
    r.ia_n = A.IsDynamic() ? Vec3(A.InvInertiaWorld() * r.ra_n) : Vec3::Zero();
    r.ib_n = B.IsDynamic() ? Vec3(B.InvInertiaWorld() * r.rb_n) : Vec3::Zero();
    r.mass_n = 1.0 / row.inv_mass_n;
    r.lambda = 0.0;
    rows_.push_back(r);
  }
  if (rows_.empty()) return 0;
  acc_v_.assign(n, Vec3::Zero());
  acc_w_.assign(n, Vec3::Zero());
  inv_mass_.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const RigidBody& b = bodies[i];
    if (!b.IsDynamic()) continue;
    inv_mass_[i] = b.inv_mass;
    acc_v_[i] = b.inv_mass * b.force;
    acc_w_[i] = b.InvInertiaWorld() * b.torque;
  }
  SolveLoads();
  SpreadOverPairs(*rows);
  // step 3: each loaded spring starts compressed by its load
  const bool linear = params.model == "linear";
  int preloaded = 0;
  for (const Row& r : rows_) {
    PenaltyRow& row = (*rows)[r.row];
    if (r.lambda <= 0.0 || row.kp <= 0.0) continue;
    const double share = r.lambda * row.nc / row.kp;
    const double compression = linear ? share : portable::Pow(share, 1.0 / params.hc_exponent);
    row.anchor.rest_depth = row.depth - compression;
    row.anchor.penetrating = true;
    row.law = EvaluateNormalLaw(params, compression, row.vn0, row.nc, row.damping, row.kp);
    ++preloaded;
  }
  return preloaded;
}

}  // namespace contactsim
