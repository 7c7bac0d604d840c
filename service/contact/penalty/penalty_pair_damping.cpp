#include "service/contact/penalty/penalty_pair_damping.h"

#include <algorithm>

#include <Eigen/Cholesky>

namespace contactsim {
namespace {

bool IsCompound(const RigidBody& body) { return body.shape.type == ShapeType::kCompound; }

}  // namespace

void PenaltyPairDamping::Prepare(const World& world, const std::vector<PenaltyRow>& rows) {
  const auto& bodies = world.bodies();
  active_ = false;
  int pairs = 0;
  for (const PenaltyRow& row : rows) {
    if (row.engaged && (IsCompound(bodies[row.a]) || IsCompound(bodies[row.b]))) active_ = true;
    pairs = std::max(pairs, row.pair + 1);
  }
  if (!active_) return;
  responses_.assign(rows.size(), Response());
  slip_.assign(pairs, Sums());
  touching_.assign(pairs, {});
  force_.assign(rows.size(), 0.0);
  for (size_t k = 0; k < rows.size(); ++k) {
    const PenaltyRow& row = rows[k];
    const RigidBody& A = bodies[row.a];
    const RigidBody& B = bodies[row.b];
    if (!row.engaged || !(IsCompound(A) || IsCompound(B))) continue;
    Response& r = responses_[k];
    r.coupled = true;
    r.pair = row.pair;
    r.inv_mass = (A.IsDynamic() ? A.inv_mass : 0.0) + (B.IsDynamic() ? B.inv_mass : 0.0);
    // the slip direction InverseEffectiveMass took for inv_mass_t (penalty_row.cpp)
    const double slip = row.vt0.norm();
    const Vec3 directions[2] = {row.n, slip > 1e-12 ? Vec3(row.vt0 / slip) : row.t1};
    Direction* out[2] = {&r.normal, &r.slip};
    const Mat3 ia = A.IsDynamic() ? A.InvInertiaWorld() : Mat3::Zero();
    const Mat3 ib = B.IsDynamic() ? B.InvInertiaWorld() : Mat3::Zero();
    for (int i = 0; i < 2; ++i) {
      Direction& d = *out[i];
      d.d = directions[i];
      d.ja = row.ra.cross(d.d);
      d.jb = row.rb.cross(d.d);
      d.ia = ia * d.ja;
      d.ib = ib * d.jb;
    }
  }
}

void PenaltyPairDamping::Accumulate(const Direction& d, double c, Sums* s) {
  s->lin += c * d.d;
  s->ang_a += c * d.ia;
  s->ang_b += c * d.ib;
}

void PenaltyPairDamping::Solve(const std::vector<PenaltyRow>& rows, const std::vector<char>& touching,
                               const std::vector<double>& shared, double h) {
  std::fill(slip_.begin(), slip_.end(), Sums());
  for (auto& points : touching_) points.clear();
  for (size_t k = 0; k < rows.size(); ++k) {
    const Response& r = responses_[k];
    force_[k] = 0.0;
    if (!r.coupled || !touching[k]) continue;
    touching_[r.pair].push_back(static_cast<int>(k));
    if (rows[k].mu > 0.0) Accumulate(r.slip, rows[k].ct, &slip_[r.pair]);
  }
  for (const std::vector<int>& points : touching_) {
    if (!points.empty()) SolvePair(rows, points, shared[points.front()], h);
  }
}

// f = -(C^-1 + h n_b K)^-1 v over the pair's touching points
void PenaltyPairDamping::SolvePair(const std::vector<PenaltyRow>& rows, const std::vector<int>& points,
                                   double shared, double h) {
  const int p = static_cast<int>(points.size());
  Eigen::MatrixXd a(p, p);
  Eigen::VectorXd v(p);
  for (int i = 0; i < p; ++i) {
    const Response& ri = responses_[points[i]];
    for (int j = 0; j <= i; ++j) {
      const Response& rj = responses_[points[j]];
      const double k = ri.inv_mass * ri.normal.d.dot(rj.normal.d) + ri.normal.ja.dot(rj.normal.ia) +
                       ri.normal.jb.dot(rj.normal.ib);
      a(i, j) = a(j, i) = h * shared * k;
    }
    const PenaltyRow& row = rows[points[i]];
    // a dashpot of 0 (no damping) takes no force: C^-1 infinite
    a(i, i) += row.law.c > 0.0 ? 1.0 / row.law.c : 1e300;
    v(i) = row.vn0;
  }
  const Eigen::VectorXd f = a.ldlt().solve(-v);
  for (int i = 0; i < p; ++i) force_[points[i]] = f(i);
}

// sum_j ct_j K_kj = (1/m_A + 1/m_B) d_k . sum ct_j d_j
//                   + (r_Ak x d_k) . sum ct_j I_A^-1 (r_Aj x d_j) + the same on B
double PenaltyPairDamping::Row(const Response& r, const Direction& d, const Sums& s) {
  return r.inv_mass * d.d.dot(s.lin) + d.ja.dot(s.ang_a) + d.jb.dot(s.ang_b);
}

double PenaltyPairDamping::Tangent(size_t k) const {
  return Row(responses_[k], responses_[k].slip, slip_[responses_[k].pair]);
}

}  // namespace contactsim
