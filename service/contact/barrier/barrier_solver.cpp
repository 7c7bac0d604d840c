#include "service/contact/barrier/barrier_solver.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "service/contact/barrier/additive_ccd.h"
#include "service/contact/barrier/affine_prediction.h"
#include "service/contact/barrier/barrier_potential.h"
#include "service/contact/contact_row.h"
#include "service/physics/integrator.h"
#include "service/physics/mass_properties.h"

namespace contactsim {
namespace {

constexpr double kFloor = 1e-2;  // of d_hat: pairs closer at the start are shifted; kappa grows below it

double BoundingRadius(const BodyGeometry& g) {
  double r = 0.0;
  for (const Vec3& X : g.points) r = std::max(r, X.norm());
  return r + g.radius;
}

// Bound on how far any point of a body of radius r moves under the step dq.
double MotionBound(const Vec12& dq, double r) {
  return dq.head<3>().norm() + dq.tail<9>().norm() * r;
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

}  // namespace

void BarrierSolver::Setup(World& world, const BarrierParams& params) {
  params_ = params;
  h_ = world.dt;
  bodies_.clear();
  dofs_ = 0;
  auto& rigid = world.bodies();
  for (size_t i = 0; i < rigid.size(); ++i) {
    RigidBody& r = rigid[i];
    Body b;
    b.index = static_cast<int>(i);
    b.geometry = MakeBodyGeometry(r.shape);
    b.radius = BoundingRadius(b.geometry);
    b.material = r.material;
    if (r.motion == MotionType::kKinematic) AdvanceBallistic(r, h_);  // prescribed: moved first, then fixed
    if (r.IsDynamic()) {
      b.dof = dofs_++;
      b.mass = AffineMassOf(r);
      b.k_ortho = params.kappa_ortho * ComputeMassProperties(r.shape, 1.0).mass;  // volume at unit density
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
    s.q_end = step != nullptr && b.dof >= 0 ? Vec12(b.q + (*step)[b.dof]) : b.q;
    s.movable = b.dof >= 0;
  }
  // (shifts are <= 0, so d - shift < d_hat needs d < d_hat)
  search_.Find(search_bodies_, d_hat, &candidates_);
  for (const CandidatePair& c : candidates_) {
    Entry e;
    e.a = c.a;
    e.b = c.b;
    e.pair = c.pair;
    if (!shift_.empty()) {
      const auto it = shift_.find(KeyOf(e.a, e.b, e.pair));
      if (it != shift_.end()) e.shift = it->second;
    }
    Evaluate(&e);
    // along a step: those that can come within d_hat by the pair's motion bound
    const double reach = step != nullptr ? RelativeMotionBound(CcdPairOf(e, *step)) : 0.0;
    if (EffectiveDistance(e) - reach < d_hat) out->push_back(e);
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
  p.dqa = A.dof >= 0 ? step[A.dof] : Vec12::Zero();
  p.dqb = B.dof >= 0 ? step[B.dof] : Vec12::Zero();
  p.pair = e.pair;
  p.shift = e.shift;
  p.signed_depth = SignedDepth();
  return p;
}

void BarrierSolver::Evaluate(Entry* e) const {
  const Body& A = bodies_[e->a];
  const Body& B = bodies_[e->b];
  const Mat3 Aa = AffineMatrix(A.q), Ab = AffineMatrix(B.q);
  e->dist = EvaluatePair(A.geometry, AffinePosition(A.q), Aa, B.geometry, AffinePosition(B.q), Ab, e->pair, SignedDepth());
  e->mollifier = MollifyEdgeEdge(A.geometry, Aa, B.geometry, Ab, e->pair);
}

void BarrierSolver::Refresh(const std::vector<Entry>& line, std::vector<Entry>* out) const {
  out->clear();
  for (Entry e : line) {
    Evaluate(&e);
    if (EffectiveDistance(e) < params_.d_hat) out->push_back(e);
  }
}

double BarrierSolver::LineSearchStart(const std::vector<Vec12>& step, const std::vector<Entry>& line) const {
  double alpha = 1.0;
  for (const Entry& e : line) alpha = AdditiveCcd(CcdPairOf(e, step), params_.ccd_fraction, alpha);
  return alpha;
}

double BarrierSolver::SignedDepth() const { return 2.0 * kFloor * params_.d_hat; }

double BarrierSolver::Energy(const std::vector<Entry>& entries) const {
  double inertia = 0.0, potential = 0.0;
  for (const Body& b : bodies_) {
    if (b.dof < 0) continue;
    const Vec12 dq = b.q - b.q_pred;
    inertia += 0.5 * dq.dot(b.mass.Times(dq));
    potential += OrthogonalityEnergy(b.q, b.k_ortho);
  }
  std::vector<PrimitivePair> unused;
  for (const Entry& e : entries) {
    const Body& A = bodies_[e.a];
    const Body& B = bodies_[e.b];
    const PairDistance d = EvaluatePair(A.geometry, AffinePosition(A.q), AffineMatrix(A.q), B.geometry,
                                        AffinePosition(B.q), AffineMatrix(B.q), e.pair, SignedDepth());
    const double b = Barrier(d.d - e.shift, params_.d_hat);
    if (!std::isfinite(b)) return std::numeric_limits<double>::infinity();
    if (b == 0.0) continue;
    potential += kappa_ * MollifyEdgeEdge(A.geometry, AffineMatrix(A.q), B.geometry, AffineMatrix(B.q), e.pair).m * b;
  }
  const double eps = params_.eps_v * h_;
  for (const Friction& f : friction_) {
    const Body& A = bodies_[f.a];
    const Body& B = bodies_[f.b];
    const Vec3 rel = (AffinePoint(B.q, f.Xb) - AffinePoint(B.q0, f.Xb)) - (AffinePoint(A.q, f.Xa) - AffinePoint(A.q0, f.Xa));
    potential += f.mu_lambda * FrictionF0((f.T.transpose() * rel).norm(), eps);
  }
  return inertia + h_ * h_ * potential;
}

void BarrierSolver::Lag(const std::vector<Entry>& entries) {
  friction_.clear();
  for (const Entry& e : entries) {
    const double d = EffectiveDistance(e);
    if (d >= params_.d_hat) continue;
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
    f.mu_lambda = mu * kappa_ * e.mollifier.m * std::abs(BarrierFirstDerivative(d, params_.d_hat));
    if (f.mu_lambda <= 0.0) continue;
    friction_.push_back(f);
  }
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
  Lag(entries);
  state_.friction.clear();
  for (const Friction& f : friction_) {
    state_.friction.push_back({rigid[bodies_[f.a].index].id, rigid[bodies_[f.b].index].id, f.Xa, f.Xb, f.T, f.mu_lambda});
  }
}

bool BarrierSolver::Advance(const std::vector<Vec12>& step, std::vector<Entry>* line, std::vector<Entry>* entries,
                            double* last_min) {
  // line search: the CCD bound, then halving until the energy decreases
  Collect(&step, line);
  double alpha = LineSearchStart(step, *line);
  const double e0 = Energy(*line);
  std::vector<Vec12> start(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) start[i] = bodies_[i].q;
  bool accepted = false;
  for (int halving = 0; halving < 40; ++halving, alpha *= 0.5) {
    for (Body& b : bodies_) {
      if (b.dof >= 0) b.q = start[&b - bodies_.data()] + alpha * step[b.dof];
    }
    if (Energy(*line) <= e0) {
      accepted = true;
      break;
    }
  }
  if (!accepted) {
    for (size_t i = 0; i < bodies_.size(); ++i) bodies_[i].q = start[i];
    return false;
  }

  // adaptive kappa: double it while the closest pair keeps closing below
  // the floor (the line's candidates hold every pair within d_hat now)
  double min_d = std::numeric_limits<double>::infinity();
  Refresh(*line, entries);
  for (const Entry& e : *entries) min_d = std::min(min_d, EffectiveDistance(e));
  if (min_d < kFloor * params_.d_hat && min_d < *last_min) kappa_ = std::min(kappa_max_, 2.0 * kappa_);
  *last_min = min_d;
  return true;
}

void BarrierSolver::StartTurningBodiesAtPrediction(std::vector<Vec12>* step, std::vector<Entry>* line,
                                                   std::vector<Entry>* entries, double* last_min) {
  bool turning = false;
  for (const Body& b : bodies_) {
    if (b.dof < 0) continue;
    Vec12& s = (*step)[b.dof];
    s = b.q_pred - b.q;
    // (where the tangent step's stretch, r |dA|^2 / 2 at a vertex, is below
    // what Newton resolves, it starts at q_n as well)
    const double turn = s.tail<9>().norm();
    if (0.5 * b.radius * turn * turn < params_.tolerance * h_) {
      s.setZero();
    } else {
      turning = true;
    }
  }
  if (turning) Advance(*step, line, entries, last_min);
}

BarrierStepResult BarrierSolver::Step(World& world, const BarrierParams& params, ContactSet* contacts) {
  BarrierStepResult result;
  if (world.bodies().size() != bodies_.size()) search_.Reset();
  Setup(world, params);
  const double d_hat = params_.d_hat, h2 = h_ * h_;

  // pairs that start closer than the floor get a shifted zero
  shift_.clear();
  std::vector<Entry> entries;
  Collect(nullptr, &entries);
  for (const Entry& e : entries) {
    // (one zero, -floor, for every pair not deeper: a pair pressed below
    // d = 0 in one step does not get a lower zero in the next)
    const double floor = kFloor * d_hat;
    if (e.dist.d < floor) shift_[KeyOf(e.a, e.b, e.pair)] = e.dist.d < -floor ? e.dist.d - floor : -floor;
  }
  Collect(nullptr, &entries);

  // initial kappa: balance the barrier's gradient against inertia and
  // orthogonality at q_n (IPC sec. 4.3), at least kappa_min
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
  {
    Eigen::VectorXd gE = Eigen::VectorXd::Zero(12 * dofs_), gB = Eigen::VectorXd::Zero(12 * dofs_);
    for (const Body& b : bodies_) {
      if (b.dof < 0) continue;
      Vec12 go;
      Mat12 unused;
      OrthogonalityDerivatives(b.q, b.k_ortho, &go, &unused);
      gE.segment<12>(12 * b.dof) = b.mass.Times(b.q - b.q_pred) + h2 * go;
    }
    for (const Entry& e : entries) {
      const double db = h2 * e.mollifier.m * BarrierFirstDerivative(EffectiveDistance(e), d_hat);
      if (bodies_[e.a].dof >= 0) gB.segment<12>(12 * bodies_[e.a].dof) -= db * AffineJacobianT(e.dist.Xa, e.dist.n);
      if (bodies_[e.b].dof >= 0) gB.segment<12>(12 * bodies_[e.b].dof) += db * AffineJacobianT(e.dist.Xb, e.dist.n);
    }
    const double gg = gB.squaredNorm();
    kappa_ = gg > 0.0 ? std::clamp(-gB.dot(gE) / gg, kappa_min, kappa_max_) : kappa_min;
  }
  // friction lagged from the end of the last step (IPC sec. 5), or from now
  // when a body restarted from its rigid state
  bool restarted = false;
  for (const Body& b : bodies_) restarted = restarted || b.restarted;
  if (restarted) {
    Lag(entries);
  } else {
    LagFromState(world);
  }

  const double eps = params_.eps_v * h_;
  double last_min = std::numeric_limits<double>::infinity();
  std::vector<Vec12> step(dofs_);
  std::vector<Entry> line;
  // turning bodies start at their prediction (affine_prediction.h)
  StartTurningBodiesAtPrediction(&step, &line, &entries, &last_min);
  // A step with a restarted body has no lag from a previous step: its
  // first lambda comes from the start of the step, which for bodies placed
  // touching (shifted pairs at 1e-2 d_hat) is many times their weight. As
  // IPC's lagged iterations (sec. 5), the minimisation is then repeated once
  // from its solution with the friction lagged there.
  const int passes = restarted && !friction_.empty() ? 2 : 1;
  for (int pass = 0; pass < passes; ++pass) {
    if (pass > 0) {
      Collect(nullptr, &entries);
      Lag(entries);
      result.converged = false;
    }
    for (int it = 0; it < params_.max_iterations && dofs_ > 0; ++it) {
      // gradient and Hessian, per-body dense 12x12 blocks
      Eigen::VectorXd g = Eigen::VectorXd::Zero(12 * dofs_);
      std::map<std::pair<int, int>, Mat12> blocks;
      for (const Body& b : bodies_) {
        if (b.dof < 0) continue;
        Vec12 go;
        Mat12 Ho;
        OrthogonalityDerivatives(b.q, b.k_ortho, &go, &Ho);
        g.segment<12>(12 * b.dof) = b.mass.Times(b.q - b.q_pred) + h2 * go;
        blocks[{b.dof, b.dof}] = b.mass.Matrix() + h2 * Ho;
      }
      // a term with gradient directions Ga (body a) and Gb (body b) and weight w:
      // g += w' [Ga; Gb], H += w'' [Ga; Gb][Ga; Gb]^T (w'' >= 0)
      // (fixed-size: Ga, Gb are 12 x 1 for a barrier pair, 12 x 2 for friction)
      // (a new block starts at zero: Eigen's fixed-size default is uninitialised)
      auto block = [&](int r, int c) -> Mat12& { return blocks.try_emplace({r, c}, Mat12::Zero()).first->second; };
      auto add = [&](int ia, int ib, const auto& Ga, const auto& Gb, const auto& grad, const auto& hess) {
        const int da = bodies_[ia].dof, db = bodies_[ib].dof;
        if (da >= 0) g.segment<12>(12 * da) += Ga * grad;
        if (db >= 0) g.segment<12>(12 * db) += Gb * grad;
        if (da >= 0) block(da, da).noalias() += Ga * hess * Ga.transpose();
        if (db >= 0) block(db, db).noalias() += Gb * hess * Gb.transpose();
        if (da >= 0 && db >= 0) {
          const Mat12 cross = Ga * hess * Gb.transpose();
          block(da, db) += cross;
          block(db, da) += cross.transpose();
        }
      };
      for (const Entry& e : entries) {
        const double d = EffectiveDistance(e);
        if (d >= d_hat) continue;
        const Vec12 Ga = -AffineJacobianT(e.dist.Xa, e.dist.n);
        const Vec12 Gb = AffineJacobianT(e.dist.Xb, e.dist.n);
        // kappa m(x) b(d): the product rule adds kappa b grad m (edge-edge);
        // the Hessian keeps the PSD Gauss-Newton part kappa m b'' grad d grad d^T
        const double m = e.mollifier.m;
        add(e.a, e.b, Ga, Gb, Eigen::Matrix<double, 1, 1>(h2 * kappa_ * m * BarrierFirstDerivative(d, d_hat)),
            Eigen::Matrix<double, 1, 1>(h2 * kappa_ * m * BarrierSecondDerivative(d, d_hat)));
        if (m < 1.0) {
          const double kb = h2 * kappa_ * Barrier(d, d_hat);
          if (bodies_[e.a].dof >= 0) g.segment<12>(12 * bodies_[e.a].dof) += kb * e.mollifier.grad_a;
          if (bodies_[e.b].dof >= 0) g.segment<12>(12 * bodies_[e.b].dof) += kb * e.mollifier.grad_b;
        }
      }
      for (const Friction& f : friction_) {
        const Body& A = bodies_[f.a];
        const Body& B = bodies_[f.b];
        const Vec3 rel = (AffinePoint(B.q, f.Xb) - AffinePoint(B.q0, f.Xb)) - (AffinePoint(A.q, f.Xa) - AffinePoint(A.q0, f.Xa));
        const Eigen::Vector2d u = f.T.transpose() * rel;
        const double y = u.norm();
        const double w = h2 * f.mu_lambda * FrictionF1OverY(y, eps);
        // Hessian of mu lambda f0(|u|) in u (IPC appendix): f1/y I +
        // (f1' y - f1) / y^3 u u^T; PSD for the f1 of barrier_potential.h:
        // for y >= eps it is (I - u u^T / y^2) / y, below eps
        // f1/y I - u u^T / (eps^2 y)
        Eigen::Matrix2d hess = w * Eigen::Matrix2d::Identity();
        if (y >= eps) {
          hess -= (w / (y * y)) * u * u.transpose();
        } else if (y > 1e-12 * eps) {
          hess -= (h2 * f.mu_lambda / (eps * eps * y)) * u * u.transpose();
        }
        Eigen::Matrix<double, 12, 2> Ga, Gb;
        for (int k = 0; k < 2; ++k) {
          Ga.col(k) = -AffineJacobianT(f.Xa, f.T.col(k));
          Gb.col(k) = AffineJacobianT(f.Xb, f.T.col(k));
        }
        add(f.a, f.b, Ga, Gb, Eigen::Vector2d(w * u), hess);
      }
      std::vector<Eigen::Triplet<double>> triplets;
      for (const auto& [key, m] : blocks) {
        for (int r = 0; r < 12; ++r) {
          for (int c = 0; c < 12; ++c) {
            if (m(r, c) != 0.0) triplets.emplace_back(12 * key.first + r, 12 * key.second + c, m(r, c));
          }
        }
      }
      Eigen::SparseMatrix<double> H(12 * dofs_, 12 * dofs_);
      H.setFromTriplets(triplets.begin(), triplets.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
      if (ldlt.info() != Eigen::Success) break;
      const Eigen::VectorXd dq = ldlt.solve(-g);
      ++result.iterations;

      // converged when every vertex would move slower than the tolerance
      double fastest = 0.0;
      for (const Body& b : bodies_) {
        if (b.dof < 0) continue;
        step[b.dof] = dq.segment<12>(12 * b.dof);
        fastest = std::max(fastest, MotionBound(step[b.dof], b.radius) / h_);
      }
      if (fastest < params_.tolerance) {
        result.converged = true;
        break;
      }

      if (!Advance(step, &line, &entries, &last_min)) break;
    }
  }

  // write back: position, rotation by polar decomposition, velocity from the
  // step, angular momentum as the midpoint rule carries it to that rotation
  // (affine_prediction.h; r.q still holds the step's start)
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
  result.min_distance = d_hat;
  for (const Entry& e : entries) {
    const double d = EffectiveDistance(e);
    if (d >= d_hat) continue;
    result.min_distance = std::min(result.min_distance, e.dist.d);
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
    c.normal_value = kappa_ * e.mollifier.m * std::abs(BarrierFirstDerivative(d, d_hat));
    contacts->push_back(c);
  }
  result.kappa = kappa_;
  Remember(world, entries);
  return result;
}

}  // namespace contactsim
