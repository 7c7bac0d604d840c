#include "service/contact/barrier/barrier_solver.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "service/contact/barrier/additive_ccd.h"
#include "service/contact/barrier/affine_prediction.h"
#include "service/contact/barrier/barrier_potential.h"
#include "service/contact/contact_row.h"
#include "service/physics/integrator.h"
#include "service/physics/mass_properties.h"

namespace contactsim {
namespace {

double BoundingRadius(const BodyGeometry& g) {
  double r = 0.0;
  for (const Vec3& X : g.points) r = std::max(r, X.norm());
  return r + g.radius;
}

using Key = std::tuple<int, int, int, int, int, bool>;
Key KeyOf(int a, int b, const PrimitivePair& p) {
  return {a, b, static_cast<int>(p.kind), p.ia, p.ib, p.swapped};
}

// A tangent basis (3x2) of the plane normal to the unit n.
Eigen::Matrix<double, 3, 2> TangentBasis(const Vec3& n) {
  const Vec3 t1 = std::abs(n.x()) < 0.57735 ? n.cross(Vec3::UnitX()).normalized() : n.cross(Vec3::UnitY()).normalized();
  Eigen::Matrix<double, 3, 2> T;
  T << t1, n.cross(t1);
  return T;
}

// kappa_ortho vol, capped at ortho_step_ratio lambda_max(S) / h^2
// (barrier_params.h).
double OrthogonalityStiffness(const BarrierParams& params, double volume, const Mat3& S, double h) {
  const double k = params.kappa_ortho * volume;
  if (params.ortho_step_ratio <= 0.0) return k;
  const double s_max = Eigen::SelfAdjointEigenSolver<Mat3>(S, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  return std::min(k, params.ortho_step_ratio * s_max / (h * h));
}

}  // namespace

void BarrierSolver::Setup(World& world, const BarrierParams& params) {
  params_ = params;
  h_ = world.dt;
  world_ = &world;
  bodies_.clear();
  dofs_ = 0;
  auto& rigid = world.bodies();
  for (size_t i = 0; i < rigid.size(); ++i) {
    RigidBody& r = rigid[i];
    Body b;
    b.index = static_cast<int>(i);
    b.geometry = MakeBodyGeometry(r.shape);
    b.geometry.surface.reach = kSurfaceReach * params.d_hat;
    b.radius = BoundingRadius(b.geometry);
    b.material = r.material;
    if (r.motion == MotionType::kKinematic) AdvanceBallistic(r, h_);  // prescribed: moved first, then fixed
    if (r.IsDynamic()) {
      b.dof = dofs_++;
      b.mass = AffineMassOf(r);
      b.k_ortho = OrthogonalityStiffness(params, ComputeMassProperties(r.shape, 1.0).mass, b.mass.S, h_);
      // the affine state carried from the last step, unless the rigid state
      // was changed from outside since (barrier_state.h)
      Vec12 qdot;
      const auto kept = state_.bodies.find(r.id);
      if (kept != state_.bodies.end() && kept->second.Matches(r)) {
        b.q0 = kept->second.q;
        qdot = kept->second.qdot;
      } else {
        RigidToAffine(r, &b.q0, &qdot);
        b.restarted = true;
      }
      // the rotation by the midpoint rule, not along A's tangent (affine_prediction.h)
      b.q_pred = PredictAffine(r, b.q0, qdot, h_);
    } else {
      b.q0 = AffineFromPose(r.x, r.Rotation());
      b.q_pred = b.q0;
    }
    b.q = b.q0;
    b.active = b.dof >= 0;
    bodies_.push_back(std::move(b));
  }
}

void BarrierSolver::Collect(const std::vector<Vec12>* step, std::vector<Entry>* out) {
  out->clear();
  const double d_hat = params_.d_hat;
  search_bodies_.resize(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    const Body& b = bodies_[i];
    SearchBody& s = search_bodies_[i];
    s.geometry = &b.geometry;
    s.q = b.q;
    s.q_end = step != nullptr && b.active ? Vec12(b.q + (*step)[b.dof]) : b.q;
    s.movable = b.active;
    s.body = &world_->bodies()[b.index];
  }
  // (shifts are <= 0, so d - shift < d_hat needs d < d_hat)
  search_.Find(search_bodies_, d_hat, world_->joined_pairs(), &candidates_);
  for (const CandidatePair& c : candidates_) {
    Entry e;
    e.a = c.a;
    e.b = c.b;
    e.pair = c.pair;
    e.width = d_hat;
    e.depth = SignedDepth();
    if (!shift_.empty()) {
      const auto it = shift_.find(KeyOf(e.a, e.b, e.pair));
      if (it != shift_.end()) {
        e.shift = it->second.shift;
        e.apart = it->second.apart;
        if (it->second.placed) {
          e.placed = true;
          e.width = kPlacedWidth * d_hat;
          e.scale = 1.0 / kPlacedWidth;
          e.depth = std::max(SignedDepth(), kFloor * d_hat - e.shift);
        }
      }
    }
    Evaluate(&e);
    // along a step: those that can come within d_hat by the pair's motion
    // bound, with each side at any fraction of its step (the islands'
    // line searches take different alphas: barrier_newton.cpp)
    const double reach = step != nullptr ? SeparateMotionBound(CcdPairOf(e, *step)) : 0.0;
    if (SearchDistance(e) - reach < d_hat) out->push_back(e);
  }
}

CcdPair BarrierSolver::CcdPairOf(const Entry& e, const std::vector<Vec12>& step) const {
  const Body& A = bodies_[e.a];
  const Body& B = bodies_[e.b];
  CcdPair p;
  p.a = &A.geometry;
  p.b = &B.geometry;
  p.qa = A.q;
  p.qb = B.q;
  p.dqa = A.active ? step[A.dof] : Vec12::Zero();
  p.dqb = B.active ? step[B.dof] : Vec12::Zero();
  p.pair = e.pair;
  p.shift = e.shift;
  p.width = e.width;
  p.signed_depth = e.depth;
  p.placed = e.placed;
  return p;
}

void BarrierSolver::Evaluate(Entry* e) const {
  const Body& A = bodies_[e->a];
  const Body& B = bodies_[e->b];
  const Mat3 Aa = AffineMatrix(A.q), Ab = AffineMatrix(B.q);
  e->dist = EvaluatePair(A.geometry, AffinePosition(A.q), Aa, B.geometry, AffinePosition(B.q), Ab, e->pair, e->depth,
                         {e->shift, e->width});
  e->mollifier = MollifyEdgeEdge(A.geometry, Aa, B.geometry, Ab, e->pair, e->dist);
}

void BarrierSolver::Refresh(const std::vector<Entry>& line, std::vector<Entry>* out) const {
  out->clear();
  for (Entry e : line) {
    Evaluate(&e);
    if (SearchDistance(e) < params_.d_hat) out->push_back(e);
  }
}

double BarrierSolver::SignedDepth() const { return 2.0 * kFloor * params_.d_hat; }

void BarrierSolver::Lag(const std::vector<Entry>& entries) {
  friction_.clear();
  for (const Entry& e : entries) {
    const double d = EffectiveDistance(e);
    if (d >= e.width) continue;
    const double mu = CombineFriction(bodies_[e.a].material, bodies_[e.b].material);
    if (mu <= 0.0) continue;
    Friction f;
    f.a = e.a;
    f.b = e.b;
    // the friction acts where the surfaces touch: a sphere's or capsule's
    // closest point is on its core (point, segment), and friction there
    // would resist the centre's motion instead of the surface's, so a
    // rolling ball or capsule would be held as if sliding; the surface
    // point is the core point moved by the radius along the normal
    // (body frame: A^-1 n, A the affine matrix)
    const Body& A = bodies_[e.a];
    const Body& B = bodies_[e.b];
    f.Xa = e.dist.Xa;
    f.Xb = e.dist.Xb;
    if (A.geometry.radius > 0.0) f.Xa += A.geometry.radius * (AffineMatrix(A.q).inverse() * e.dist.n);
    if (B.geometry.radius > 0.0) f.Xb -= B.geometry.radius * (AffineMatrix(B.q).inverse() * e.dist.n);
    f.T = TangentBasis(e.dist.n);
    f.mu_lambda = mu * kappa_ * e.scale * e.mollifier.m * std::abs(BarrierFirstDerivative(d, e.width));
    if (f.mu_lambda <= 0.0) continue;
    friction_.push_back(f);
  }
}

bool BarrierSolver::LagSettled(const std::vector<Friction>& used, const std::vector<Friction>& now,
                               double tolerance) {
  // per pair of bodies, the sum of its pairs' mu lambda: the primitive
  // pairs within reach come and go at the solution while the bodies' load
  // on each other stays
  std::map<std::pair<int, int>, double> change;
  double largest = 0.0;
  for (const Friction& f : now) {
    double& sum = change[{f.a, f.b}];
    sum += f.mu_lambda;
    largest = std::max(largest, sum);
  }
  for (const Friction& f : used) change[{f.a, f.b}] -= f.mu_lambda;
  for (const auto& [bodies, delta] : change) {
    if (std::abs(delta) > tolerance * largest) return false;
  }
  return true;
}

void BarrierSolver::LagFromState(const World& world) {
  friction_.clear();
  std::map<BodyId, int> index;
  for (size_t i = 0; i < bodies_.size(); ++i) index[world.bodies()[bodies_[i].index].id] = static_cast<int>(i);
  for (const LaggedFriction& l : state_.friction) {
    const auto a = index.find(l.a), b = index.find(l.b);
    if (a == index.end() || b == index.end()) continue;
    friction_.push_back({a->second, b->second, l.Xa, l.Xb, l.T, l.mu_lambda});
  }
}

void BarrierSolver::Remember(const World& world, const std::vector<Entry>& entries) {
  const auto& rigid = world.bodies();
  std::map<BodyId, AffineBodyState> kept;
  for (const Body& b : bodies_) {
    if (b.dof < 0) continue;
    AffineBodyState& s = kept[rigid[b.index].id];
    s.q = b.q;
    s.qdot = (b.q - b.q0) / h_;   // (its rotational rows predict nothing: affine_prediction.h)
    s.Stamp(rigid[b.index]);
  }
  state_.bodies = std::move(kept);
  // the placed pairs still within d_hat stay placed
  state_.placed.clear();
  for (const Entry& e : entries) {
    if (!e.placed || e.dist.d >= params_.d_hat) continue;
    state_.placed.push_back({rigid[bodies_[e.a].index].id, rigid[bodies_[e.b].index].id, static_cast<int>(e.pair.kind),
                             e.pair.ia, e.pair.ib, e.pair.swapped, e.shift});
  }
  Lag(entries);
  state_.friction.clear();
  for (const Friction& f : friction_) {
    state_.friction.push_back({rigid[bodies_[f.a].index].id, rigid[bodies_[f.b].index].id, f.Xa, f.Xb, f.T, f.mu_lambda});
  }
}

void BarrierSolver::InitialKappa(const World& world, const std::vector<Entry>& entries) {
  const double d_hat = params_.d_hat, h2 = h_ * h_;
  double mass_sum = 0.0;
  int dynamic = 0;
  for (const Body& b : bodies_) {
    if (b.dof >= 0) mass_sum += b.mass.m, ++dynamic;
  }
  // (a quarter of the weight per pair: a box face resting on its four
  // corners at d_hat / 2 is then in balance, not launched by 4 m g)
  const double kappa_min = 0.25 * (dynamic > 0 ? mass_sum / dynamic : 1.0) * std::max(world.gravity.norm(), 1.0) /
                           std::abs(BarrierFirstDerivative(0.5 * d_hat, d_hat));
  kappa_max_ = 1e6 * kappa_min;
  // balance the barrier's gradient against inertia and orthogonality at q_n
  Eigen::VectorXd gE = Eigen::VectorXd::Zero(12 * dofs_), gB = Eigen::VectorXd::Zero(12 * dofs_);
  for (const Body& b : bodies_) {
    if (b.dof < 0) continue;
    Vec12 go;
    Mat12 unused;
    OrthogonalityDerivatives(b.q, b.k_ortho, &go, &unused);
    gE.segment<12>(12 * b.dof) = b.mass.Times(b.q - b.q_pred) + h2 * go;
  }
  for (const Entry& e : entries) {
    const double db = h2 * e.scale * e.mollifier.m * BarrierFirstDerivative(EffectiveDistance(e), e.width);
    if (bodies_[e.a].dof >= 0) gB.segment<12>(12 * bodies_[e.a].dof) -= db * AffineJacobianT(e.dist.Xa, e.dist.n);
    if (bodies_[e.b].dof >= 0) gB.segment<12>(12 * bodies_[e.b].dof) += db * AffineJacobianT(e.dist.Xb, e.dist.n);
  }
  const double gg = gB.squaredNorm();
  kappa_ = gg > 0.0 ? std::clamp(-gB.dot(gE) / gg, kappa_min, kappa_max_) : kappa_min;
}

void BarrierSolver::WriteBack(World& world, const std::vector<Entry>& entries, ContactSet* contacts,
                              BarrierStepResult* result) const {
  // position, rotation by polar decomposition, velocity from the step,
  // angular momentum as the midpoint rule carries it to that rotation
  // (affine_prediction.h; r.q still holds the step's start)
  const double d_hat = params_.d_hat;
  auto& rigid = world.bodies();
  for (const Body& b : bodies_) {
    if (b.dof < 0) continue;
    RigidBody& r = rigid[b.index];
    const Quat rotation = Quat(NearestRotation(AffineMatrix(b.q))).normalized();
    const Vec3 x = AffinePosition(b.q);
    r.P = r.mass * (x - AffinePosition(b.q0)) / h_;
    r.L = EndAngularMomentum(r, r.q, rotation, h_);
    r.x = x;
    r.q = rotation;
  }
  // contacts and the smallest distance at the end (entries are those at q)
  contacts->clear();
  result->min_distance = d_hat;
  for (const Entry& e : entries) {
    const double d = EffectiveDistance(e);
    if (d >= e.width) continue;
    result->min_distance = std::min(result->min_distance, e.dist.d);
    const Body& A = bodies_[e.a];
    const Body& B = bodies_[e.b];
    Contact c;
    c.a = A.index;
    c.b = B.index;
    c.id_a = rigid[A.index].id;
    c.id_b = rigid[B.index].id;
    const Vec3 ca = AffinePoint(A.q, e.dist.Xa), cb = AffinePoint(B.q, e.dist.Xb);
    c.point = 0.5 * (ca + cb);
    c.normal = e.dist.n;
    c.depth = -e.dist.d;
    c.feature_id = static_cast<uint32_t>(static_cast<int>(e.pair.kind) * 1000003 + e.pair.ia * 1009 + e.pair.ib * 2 + e.pair.swapped);
    c.normal_value = kappa_ * e.scale * e.mollifier.m * std::abs(BarrierFirstDerivative(d, e.width));
    contacts->push_back(c);
  }
}

void BarrierSolver::TakeShifts(const World& world) {
  const double d_hat = params_.d_hat, floor = kFloor * d_hat;
  shift_.clear();
  // the placed pairs kept from the last step, for bodies still present
  std::map<BodyId, int> index;
  for (size_t i = 0; i < bodies_.size(); ++i) index[world.bodies()[bodies_[i].index].id] = static_cast<int>(i);
  for (const PlacedPair& p : state_.placed) {
    const auto a = index.find(p.a), b = index.find(p.b);
    if (a == index.end() || b == index.end()) continue;
    const PrimitivePair pair{static_cast<PrimitiveKind>(p.kind), p.ia, p.ib, p.swapped};
    shift_[KeyOf(a->second, b->second, pair)] = {p.zero, false, true};
  }
  std::vector<Entry> entries;
  Collect(nullptr, &entries);
  // the pairs of bodies that start, measured as deep as a placement can
  // overlap, and the body pairs that overlap (a pair deeper than floor)
  std::set<std::pair<int, int>> overlapping;
  for (Entry& e : entries) {
    if (!bodies_[e.a].restarted && !bodies_[e.b].restarted) continue;
    e.depth = kPlacedDepth * d_hat;
    Evaluate(&e);
    if (e.dist.d < -floor) overlapping.insert({e.a, e.b});
  }
  for (const Entry& e : entries) {
    const bool starts = bodies_[e.a].restarted || bodies_[e.b].restarted;
    // a kept zero stays, unless a body that starts again is at or below it
    if (e.placed && (!starts || e.dist.d - e.shift > 0.0)) continue;
    if (starts) {
      const Key key = KeyOf(e.a, e.b, e.pair);
      const bool polyhedral = bodies_[e.a].geometry.radius == 0.0 && bodies_[e.b].geometry.radius == 0.0;
      if (!e.dist.is_signed && polyhedral && (e.dist.d < SignedDepth() || overlapping.count({e.a, e.b}) > 0)) {
        // an unsigned distance inside an overlap, or one that can turn
        // signed (EvaluatePair, at its triangle's or edge's border, within
        // the signed depth), is no separation: its zero is where the same
        // distance behind a face would be, so the pair exerts nothing until
        // it turns signed and deeper
        shift_[key] = {-e.dist.d - kPlacedWidth * d_hat, false, true};
      } else if (e.dist.d < kPlacedReach * d_hat) {
        shift_[key] = {e.dist.d - kPlacedWidth * d_hat, false, true};
      } else {
        shift_.erase(key);
      }
      continue;
    }
    // (one zero, -floor, for every pair not deeper: a pair pressed below
    // d = 0 in one step does not get a lower zero in the next)
    if (e.dist.d < floor) {
      shift_[KeyOf(e.a, e.b, e.pair)] = {e.dist.d < -floor ? e.dist.d - floor : -floor, e.dist.d > kTouch * d_hat, false};
    }
  }
}

BarrierStepResult BarrierSolver::Step(World& world, const BarrierParams& params, ContactSet* contacts) {
  BarrierStepResult result;
  if (world.bodies().size() != bodies_.size()) search_.Reset();
  Setup(world, params);

  TakeShifts(world);
  std::vector<Entry> entries;
  Collect(nullptr, &entries);
  InitialKappa(world, entries);
  std::vector<std::pair<int, int>> start_pairs;
  for (const Entry& e : entries) start_pairs.emplace_back(e.a, e.b);

  // friction lagged from the end of the last step (IPC sec. 5), or from now
  // when a body restarted from its rigid state
  bool restarted = false;
  for (const Body& b : bodies_) restarted = restarted || b.restarted;
  if (restarted) {
    Lag(entries);
  } else {
    LagFromState(world);
  }

  double last_min = std::numeric_limits<double>::infinity();
  std::vector<Vec12> step(dofs_);
  std::vector<Entry> line;
  // turning bodies start at their prediction (affine_prediction.h)
  StartTurningBodiesAtPrediction(&step, &line, &entries, &last_min);
  // IPC's lagged iterations (sec. 5): the minimisation is repeated from its
  // solution with the friction lagged there until the lag settles
  // (barrier_params.h). A step with a restarted body has no lag from a
  // previous step: its first lambda comes from the start of the step, which
  // for bodies placed touching (shifted pairs at 1e-2 d_hat) is many times
  // their weight, so it always takes a second pass.
  const int passes = std::max(params.friction_lag_passes, restarted ? 2 : 1);
  for (int pass = 1;; ++pass) {
    Minimise(&entries, &last_min, &result);
    if (friction_.empty() || pass >= passes) break;
    ActivateAll();
    Collect(nullptr, &entries);
    std::vector<Friction> used = std::move(friction_);
    Lag(entries);
    if (!(restarted && pass == 1) && LagSettled(used, friction_, params.friction_lag_tolerance)) {
      friction_ = std::move(used);  // the friction the solution was found with
      break;
    }
  }

  // every pair within d_hat at the end, for the contacts and the lag
  ActivateAll();
  Collect(nullptr, &entries);
  if (BalanceMomentum(std::move(start_pairs), entries)) Collect(nullptr, &entries);
  WriteBack(world, entries, contacts, &result);
  result.kappa = kappa_;
  Remember(world, entries);
  return result;
}

}  // namespace contactsim
