#include "service/contact/penalty/penalty_explicit.h"

#include <algorithm>
#include <cmath>

#include "service/contact/joints/joint_solver.h"
#include "service/contact/penalty/penalty_damping_bound.h"
#include "service/contact/penalty/penalty_impacts.h"
#include "service/contact/penalty/penalty_pair_damping.h"
#include "service/contact/penalty/penalty_stiffness.h"
#include "service/physics/integrator.h"

namespace contactsim {

int ExplicitSubsteps(const World& world, const std::vector<PenaltyRow>& rows, const PenaltyParams& params,
                     double dt) {
  constexpr int kMaxSubsteps = 1000;
  // symplectic Euler is stable below omega h = 2; half of it leaves room for
  // the power iteration's shortfall and for modes the rows at the step's
  // start did not see
  constexpr double kStableOmegaH = 1.0;
  // With dashpots that take a share b of a mode's velocity each sub-step,
  // the bound falls to (omega h)^2 <= 4 - 2 b. A light body pressed by
  // springs set for a heavier one has its dashpots cut to about 1 / h
  // (stage 2 of ExplicitStep), and the corners of a light box between the
  // ground and a heavy plank added up to b = 1.7 in its rocking: at
  // omega h = 0.78 it rocked in a limit cycle and walked 0.2 mm a second,
  // less but still at ratios of 3 to 8 (docs/methods/penalty.md, "Explicit
  // integrator").
  // Half the step again held every resting ratio from 2 up; a light box
  // struck by a landing body up to 100 times heavier needs 0.3 (b up to
  // 1.8): at 0.5 three of 40 mixed-mass random scenes pressed one 43-72 mm
  // into the ground and threw it at up to 24 m/s, at 0.4 one still sank
  // 30 mm ("Random scenes"). Equal masses keep the longer step.
  constexpr double kHeavyOnLightRatio = 2.0;
  constexpr double kHeavyOnLightOmegaH = 0.3;
  const ContactOmega omega = ContactOmegas(world, rows);
  const double stable = omega.mass_ratio >= kHeavyOnLightRatio ? kHeavyOnLightOmegaH : kStableOmegaH;
  const double needed = std::max(std::ceil(omega.point * dt / params.max_omega_h),
                                 std::ceil(omega.estimate * dt / stable));
  return std::max(params.substeps, static_cast<int>(std::min<double>(needed, kMaxSubsteps)));
}

namespace {

// The part of a lever arm that stays put as its body turns: a sphere's or a
// capsule's contact point is its radius along the outward normal from the
// centre (or the axis), wherever the body has turned. Tracking the material
// point instead lifted a rolling sphere's contact by r (w h)^2 / 2 within a
// step, more than its resting depth, and it chattered and slipped.
Vec3 RoundOffset(const RigidBody& body, const Vec3& outward) {
  const ShapeType type = body.shape.type;
  return type == ShapeType::kSphere || type == ShapeType::kCapsule ? Vec3(body.shape.radius * outward) : Vec3::Zero();
}

// What a row keeps over the step besides PenaltyRow: its frame at the
// step's start and what its last sub-step left.
struct RowFrame {
  double depth0 = 0.0;        // m, depth at the step's start
  Vec3 ra0, rb0;              // m, lever arms at the step's start, less the round part (RoundOffset)
  Vec3 ua, ub;                // m, world: the round part of each arm, which does not turn with its body
  Vec3 ra, rb;                // m, lever arms now
  Vec3 v = Vec3::Zero();      // m/s, v_B - v_A at the point now
  bool touching = false;
  bool carried = false;       // held by a sticking anchor in the last sub-step
};

class ExplicitStepper {
 public:
  ExplicitStepper(World& world, std::vector<PenaltyRow>& rows, const PenaltyParams& params, double h,
                  PenaltyImpacts* impacts)
      : world_(world), rows_(rows), params_(params), h_(h), linear_(params.model == "linear"),
        impacts_(params.impacts == "sequential" ? impacts : nullptr),
        impact_threshold_(PenaltyImpactThreshold(world, params.impact_threshold)) {
    const auto& bodies = world.bodies();
    const size_t n = bodies.size();
    x0_.resize(n), R0t_.resize(n), force_.resize(n), torque_.resize(n), rotation_.resize(n);
    v_.resize(n), w_.resize(n), pushed_.assign(n, false), pairs_.assign(n, 0.0);
    reach_.assign(n, 0.0), ahead_.assign(n, 0.0), radius_.assign(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      x0_[i] = bodies[i].x;
      R0t_[i] = bodies[i].Rotation().transpose();
      if (bodies[i].motion != MotionType::kStatic) radius_[i] = BoundingRadius(bodies[i]);
      rotation_[i].setIdentity();
      v_[i].setZero();
      w_[i].setZero();
      force_[i] = bodies[i].force;
      torque_[i] = bodies[i].torque;
    }
    frames_.resize(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      const PenaltyRow& row = rows[k];
      RowFrame& f = frames_[k];
      f.depth0 = row.depth;
      f.ua = RoundOffset(bodies[row.a], row.n);
      f.ub = RoundOffset(bodies[row.b], -row.n);
      f.ra = row.ra;
      f.rb = row.rb;
      f.ra0 = row.ra - f.ua;
      f.rb0 = row.rb - f.ub;
    }
    // a pair touching at the step's start began before it
    int pairs = 0;
    for (const PenaltyRow& row : rows) pairs = std::max(pairs, row.pair + 1);
    pair_touching_.assign(pairs, 0);
    pair_touched_.assign(pairs, 0);
    for (const PenaltyRow& row : rows) {
      if (row.engaged && row.depth > row.anchor.rest_depth) pair_touching_[row.pair] = 1;
    }
    pair_damping_.Prepare(world, rows);
    damping_bound_.Prepare(world, rows, h, linear_);
    // a step whose rows can hold no impact (restitution = off, or friction
    // and e = 0 in held components only) runs none of the stage
    if (impacts_ != nullptr && !MayHoldImpact(world, rows)) impacts_ = nullptr;
  }

  void Substep(ExplicitStats* stats) {
    Pass(stats, true);
    IntegrateMomenta(world_, h_);
    SolveJointVelocities(world_, h_);  // on the new momenta, before the positions use them
    MovePositions();
    ProjectJointPositions(world_);
  }

  // the last sub-step's slip into the anchors, the end depths into the rows,
  // and the external wrench back into the bodies
  void Finish(ExplicitStats* stats) {
    Pass(stats, false);
    auto& bodies = world_.bodies();
    for (size_t i = 0; i < bodies.size(); ++i) bodies[i].force = force_[i], bodies[i].torque = torque_[i];
  }

 private:
  // x += v h with the new momenta (symplectic Euler) for bodies a contact
  // pushed in this sub-step; the others fly ballistically,
  // x += (v1 - F h / (2 m)) h = v0 h + F h^2 / (2 m), exact under a constant
  // wrench, so that a bounce's flight carries no O(h) bias (as the impulse
  // method's AdvanceBallistic: docs/methods/penalty.md). Not in worlds with joints,
  // whose solve changed the momenta after the wrench.
  void MovePositions() {
    auto& bodies = world_.bodies();
    const bool ballistic = world_.joints().empty();
    if (ballistic) {
      for (size_t i = 0; i < bodies.size(); ++i) {
        if (pushed_[i] || !bodies[i].IsDynamic()) continue;
        bodies[i].P -= 0.5 * h_ * force_[i];
        bodies[i].L -= 0.5 * h_ * torque_[i];
      }
    }
    IntegratePositions(world_, h_);
    if (ballistic) {
      for (size_t i = 0; i < bodies.size(); ++i) {
        if (pushed_[i] || !bodies[i].IsDynamic()) continue;
        bodies[i].P += 0.5 * h_ * force_[i];
        bodies[i].L += 0.5 * h_ * torque_[i];
      }
    }
  }

  // One pass over the rows: stage 1 for each, then with `apply` stages 2-4.
  // The damping's pair counts are this pass's: counted a sub-step late (to
  // read each row once), a light box pressed by a 1,000 times heavier plank
  // rocked with its corners touching in turn, each sub-step saw the wrong
  // count, and the box flew off.
  void Pass(ExplicitStats* stats, bool apply) {
    PrepareBodies();
    auto& bodies = world_.bodies();
    std::fill(pairs_.begin(), pairs_.end(), 0.0);
    pair_touched_.swap(pair_touching_);
    std::fill(pair_touching_.begin(), pair_touching_.end(), 0);
    for (size_t k = 0; k < rows_.size(); ++k) {
      if (rows_[k].engaged) MeasureRow(k, stats);
    }
    if (!apply) return;
    if (impacts_ != nullptr && ResolveImpacts()) RemeasureVelocities();
    if (pair_damping_.active()) SolvePairDamping();
    for (size_t i = 0; i < bodies.size(); ++i) bodies[i].force = force_[i], bodies[i].torque = torque_[i];
    std::fill(pushed_.begin(), pushed_.end(), false);
    for (size_t k = 0; k < rows_.size(); ++k) {
      if (rows_[k].engaged) ApplyRow(k);
    }
  }

  // each body's turn since the step's start, velocities now, and reach
  void PrepareBodies() {
    const auto& bodies = world_.bodies();
    for (size_t i = 0; i < bodies.size(); ++i) {
      const RigidBody& b = bodies[i];
      if (b.motion == MotionType::kStatic) continue;  // identity and rest, as set up
      const Mat3 R = b.Rotation();
      rotation_[i].noalias() = R * R0t_[i];
      v_[i] = b.LinearVelocity();
      // w = R I_b^-1 R^T L, without forming I^-1 in the world frame
      w_[i] = b.IsDynamic() ? Vec3(R * (b.inv_inertia_body * (R.transpose() * b.L))) : b.AngularVelocity();
    }
    // the last sub-step moved each body with these velocities (ballistic
    // ones with v - F h / (2 m))
    if (measured_) {
      for (size_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].motion == MotionType::kStatic) continue;
        const double ballistic = 0.5 * h_ * bodies[i].inv_mass * force_[i].norm();
        reach_[i] += h_ * (v_[i].norm() + ballistic + w_[i].norm() * radius_[i]);
      }
    }
    measured_ = true;
    // the impact stage takes a pair as it closes within the coming
    // sub-step, so its rows are measured one sub-step's motion ahead
    if (impacts_ != nullptr) {
      for (size_t i = 0; i < bodies.size(); ++i) {
        if (bodies[i].motion == MotionType::kStatic) continue;
        ahead_[i] = h_ * (v_[i].norm() + w_[i].norm() * radius_[i]);
      }
    }
  }

  // stage 1: the row's depth and velocity now; its anchor advances by the
  // last sub-step's slip
  void MeasureRow(size_t k, ExplicitStats* stats) {
    const auto& bodies = world_.bodies();
    PenaltyRow& row = rows_[k];
    RowFrame& f = frames_[k];
    // no point of either body has moved farther than its reach: a gap
    // wider than both is still open (most speculative rows of a pile). The
    // gap is the spring's where a placed start compressed it (a negative
    // rest depth, penalty_preload.h): such a row bites at a depth below 0,
    // and skipped in a step's first sub-step, one of a lying capsule's two
    // points let it tip and roll off at 0.27 mm/s.
    if (std::max(f.depth0, f.depth0 - row.anchor.rest_depth) + reach_[row.a] + reach_[row.b] + ahead_[row.a] +
            ahead_[row.b] <
        0.0) {
      f.touching = false;
      return;
    }
    const Vec3 ra = rotation_[row.a] * f.ra0, rb = rotation_[row.b] * f.rb0;
    const Vec3 dp = (bodies[row.b].x - x0_[row.b] + rb - f.rb0) - (bodies[row.a].x - x0_[row.a] + ra - f.ra0);
    f.ra = ra + f.ua;
    f.rb = rb + f.ub;
    row.depth = f.depth0 - row.n.dot(dp);
    f.v = v_[row.b] + w_[row.b].cross(f.rb) - v_[row.a] - w_[row.a].cross(f.ra);
    if (f.carried) row.anchor.stretch += h_ * (f.v - row.n * row.n.dot(f.v));
    stats->max_penetration = std::max(stats->max_penetration, row.depth);
    // the spring starts at the placed overlap left (penalty_row.h)
    const double spring_depth = row.depth - row.anchor.rest_depth;
    f.touching = spring_depth > 0.0;
    if (!f.touching) return;
    row.vn0 = row.n.dot(f.v);
    row.vt0 = f.v - row.n * row.vn0;
    if (linear_) {  // EvaluateNormalLaw's linear law, without its string compare per point
      row.law.k = row.kp / row.nc;
      row.law.c = row.damping / row.nc;
      row.law.lambda0 = row.law.k * spring_depth - row.law.c * row.vn0;
    } else {
      row.law = EvaluateNormalLaw(params_, spring_depth, row.vn0, row.nc, row.damping, row.kp);
    }
    if (bodies[row.a].IsDynamic()) pairs_[row.a] += 1.0 / row.nc;
    if (bodies[row.b].IsDynamic()) pairs_[row.b] += 1.0 / row.nc;
    pair_touching_[row.pair] = 1;
  }

  // the impact stage (penalty_impacts.h) on this pass's touching points
  bool ResolveImpacts() {
    arms_.resize(rows_.size());
    for (size_t k = 0; k < rows_.size(); ++k) {
      arms_[k].ra = frames_[k].ra;
      arms_[k].rb = frames_[k].rb;
      const PenaltyRow& row = rows_[k];
      const Vec3 v = v_[row.b] + w_[row.b].cross(frames_[k].rb) - v_[row.a] - w_[row.a].cross(frames_[k].ra);
      arms_[k].vn = row.n.dot(v);
      arms_[k].spring_depth = row.depth - row.anchor.rest_depth;
    }
    return impacts_->Resolve(world_, rows_, arms_, impact_threshold_, h_, world_.dt);
  }

  // after the impact stage's impulses: each body's velocities, and each
  // touching row's velocity, law and whether its spring still bites (the
  // stage moved the struck rows' rest depth to their depth)
  void RemeasureVelocities() {
    const auto& bodies = world_.bodies();
    for (size_t i = 0; i < bodies.size(); ++i) {
      if (!bodies[i].IsDynamic()) continue;
      v_[i] = bodies[i].LinearVelocity();
      w_[i] = bodies[i].AngularVelocity();
    }
    for (size_t k = 0; k < rows_.size(); ++k) {
      PenaltyRow& row = rows_[k];
      RowFrame& f = frames_[k];
      if (!row.engaged || !f.touching) continue;
      const double spring_depth = row.depth - row.anchor.rest_depth;
      if (spring_depth <= 0.0) {
        f.touching = false;
        if (bodies[row.a].IsDynamic()) pairs_[row.a] -= 1.0 / row.nc;
        if (bodies[row.b].IsDynamic()) pairs_[row.b] -= 1.0 / row.nc;
        continue;
      }
      f.v = v_[row.b] + w_[row.b].cross(f.rb) - v_[row.a] - w_[row.a].cross(f.ra);
      row.vn0 = row.n.dot(f.v);
      row.vt0 = f.v - row.n * row.vn0;
      row.law = EvaluateNormalLaw(params_, spring_depth, row.vn0, row.nc, row.damping, row.kp);
    }
  }

  // the coupled dashpots of this pass's touching points, by pair
  // (penalty_pair_damping.h)
  void SolvePairDamping() {
    touching_.resize(rows_.size());
    shared_.resize(rows_.size());
    for (size_t k = 0; k < rows_.size(); ++k) {
      const PenaltyRow& row = rows_[k];
      touching_[k] = row.engaged && frames_[k].touching;
      shared_[k] = std::max(1.0, std::max(pairs_[row.a], pairs_[row.b]));
    }
    pair_damping_.Solve(rows_, touching_, shared_, h_);
  }

  // stages 2-4: normal force with its onset, friction, into the bodies
  void ApplyRow(size_t k) {
    auto& bodies = world_.bodies();
    PenaltyRow& row = rows_[k];
    RowFrame& f = frames_[k];
    f.carried = false;
    if (!f.touching) {
      // a point that lets go loses its anchor (penalty_friction.h)
      row.lambda = 0.0, row.ft.setZero(), row.sliding = false;
      row.anchor.stretch.setZero();
      row.anchor.penetrating = false;
      return;
    }
    const double shared = std::max(1.0, std::max(pairs_[row.a], pairs_[row.b]));
    const bool coupled = pair_damping_.Coupled(k);
    const double scale = damping_bound_.Scale(k, shared);
    double cn = scale * row.law.c / (1.0 + h_ * shared * row.law.c * row.inv_mass_n);
    double lambda = row.law.lambda0 + (row.law.c - cn) * row.vn0;
    if (coupled) {
      // the pair's dashpots solved together: the force in place of c vn0,
      // and for the onset's room an equivalent dashpot at the approach
      const double f = pair_damping_.NormalForce(k);
      lambda = row.law.lambda0 + row.law.c * row.vn0 + f;
      cn = row.vn0 < 0.0 ? std::max(0.0, f / -row.vn0) : cn;
    }
    // the onset (penalty_row.h) belongs to a pair's impact: only when none
    // of its points touched in the last sub-step. Given to each corner of
    // a rocking box as it came down again, m_eff / nc each, it reversed
    // the rocking 2.2 times faster each sub-step (a corner's own effective
    // mass is less than m_eff / nc).
    // It may take no more momentum than stops the point itself: its own
    // effective mass 1 / K can be far below m_eff / nc (the edge of a thin
    // plate spinning into a sphere), and the share alone reversed such a
    // point past zero and gave the pair energy (docs/methods/penalty.md,
    // "Onset correction"); a cube's corner landing flat has 1 / K = m / 4, the share.
    if (!row.anchor.penetrating && !pair_touched_[row.pair]) {
      const double approach = std::max(0.0, -row.vn0);
      const double mass = row.inv_mass_n > 0.0 ? std::min(row.m_share, 1.0 / row.inv_mass_n) : row.m_share;
      const double room = std::max(0.0, mass * approach - cn * approach * h_);
      lambda += std::min(row.law.c * std::min(row.depth - row.anchor.rest_depth, approach * h_), room) / h_;
    }
    row.anchor.penetrating = true;
    row.lambda = std::max(0.0, lambda);
    row.ft.setZero();
    row.sliding = false;
    if (row.mu > 0.0) {
      // a coupled pair's friction dashpots take the larger of the point's own
      // response and its pair's (penalty_pair_damping.h)
      const double own = row.ct * row.inv_mass_t;
      const double pair = coupled ? pair_damping_.Tangent(k) : 0.0;
      const double ct = pair > own ? row.ct / (1.0 + h_ * shared * pair)
                                   : row.ct / (1.0 + h_ * shared * row.ct * row.inv_mass_t);
      const Vec3 trial = -row.kt * row.anchor.stretch - ct * row.vt0;
      row.ft = CoulombLimit(trial, row.mu * row.lambda, &row.sliding);
      if (row.sliding) row.anchor.stretch = -row.ft / row.kt;
      f.carried = row.lambda > 0.0 && !row.sliding;
    }
    if (row.lambda <= 0.0) return;
    pushed_[row.a] = pushed_[row.b] = true;
    const Vec3 force = row.lambda * row.n + row.ft;  // on B; -force on A
    if (bodies[row.b].IsDynamic()) {
      bodies[row.b].force += force;
      bodies[row.b].torque += f.rb.cross(force);
    }
    if (bodies[row.a].IsDynamic()) {
      bodies[row.a].force -= force;
      bodies[row.a].torque -= f.ra.cross(force);
    }
  }

  World& world_;
  std::vector<PenaltyRow>& rows_;
  const PenaltyParams& params_;
  double h_;
  bool linear_;
  PenaltyImpacts* impacts_;  // null: impacts = springs
  double impact_threshold_;  // m/s (PenaltyImpactThreshold)
  std::vector<ImpactArms> arms_;
  std::vector<Vec3> x0_, force_, torque_, v_, w_;
  std::vector<Mat3> R0t_, rotation_;
  // per dynamic body: touching pairs, sum of 1 / nc over its touching
  // points in this pass
  std::vector<double> pairs_;
  std::vector<RowFrame> frames_;
  // per body pair: a point of it touched in the last pass, and in this one
  std::vector<char> pair_touched_, pair_touching_;
  PenaltyPairDamping pair_damping_;  // the pairs with a compound body
  PenaltyDampingBound damping_bound_;
  std::vector<char> touching_;       // per row, for pair_damping_
  std::vector<double> shared_;       // per row: n_b, for pair_damping_
  std::vector<bool> pushed_;  // per body: a contact force acted in this sub-step
  std::vector<double> reach_;   // m, per body: how far any of its points may have moved since the step's start
  std::vector<double> ahead_;   // m, per body: how far they may move in the coming sub-step (impact stage only)
  std::vector<double> radius_;  // m, per body: BoundingRadius
  bool measured_ = false;       // Measure ran before (reach_ counts from the second call)
};

}  // namespace

ExplicitStats ExplicitStep(World& world, std::vector<PenaltyRow>& rows, const PenaltyParams& params, double dt,
                           int substeps, PenaltyImpacts* impacts) {
  ExplicitStats stats;
  stats.substeps = substeps;
  ExplicitStepper stepper(world, rows, params, dt / substeps, impacts);
  for (int s = 0; s < substeps; ++s) stepper.Substep(&stats);
  stepper.Finish(&stats);
  return stats;
}

}  // namespace contactsim
