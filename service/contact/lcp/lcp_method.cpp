#include "service/contact/lcp/lcp_method.h"

#include <algorithm>

#include "service/contact/contact_row.h"
#include "service/contact/joint_substeps.h"
#include "service/contact/jointed_contacts.h"
#include "service/contact/joints/joint_solver.h"
#include "service/contact/lcp/lcp_contact_rows.h"
#include "service/contact/lcp/lemke_components.h"
#include "service/contact/lcp/lemke_rows.h"
#include "service/contact/patch_torsion.h"
#include "service/physics/integrator.h"

namespace contactsim {
namespace {

// bodies a thread takes at a time (solver_body.cpp says why 64)
constexpr int kLcpBodyGrain = 64;
// A solve may add this fraction of the kinetic energy before it (round-off
// and the products' ordinary give and take) before it is solved again
// without the velocity products (SolveWithinEnergy).
constexpr double kEnergyGuard = 1e-6;
// m/s: the tolerance of lemke's PGS fallback at most (LcpMethod::Solve)
constexpr double kLemkeFallbackTolerance = 1e-6;

// `velocities`: the rows act on velocities (the energy guard applies), not
// on the split impulse's pseudo-velocities.
SubspaceOptions SubspaceOptionsOf(const LcpParams& p, bool velocities) {
  SubspaceOptions options;
  options.mass_ratio = p.direct_mass_ratio;
  options.max_rows = p.direct_max_rows;
  options.energy_guard = velocities;
  return options;
}

}  // namespace

Status LcpMethod::SetParams(const ParamMap& params) {
  return LcpParamTable().Parse(Name(), params, params_, &params_);
}

Status LcpMethod::LoadState(const std::string& bytes) {
  if (warm_start_.Restore(bytes)) return Status::Ok();
  return Status::InvalidArgument("lcp method state: malformed warm-start impulses (" + std::to_string(bytes.size()) +
                                 " bytes)");
}

void LcpMethod::CorrectPositions(World& world, const ContactSet& contacts, const std::vector<Impact>& impacts,
                                 ParallelRunner& runner) {
  const bool split = params_.drift == "split" && params_.erp > 0.0;
  split_rows_.clear();
  LoadSolverBodies(world, runner, &bodies_);
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    // m of separation this step (pseudo-velocity x 1 step): an impact's
    // exact end position (lcp_contact_rows.h, under either drift rule, as
    // it is not drift), else erp of the penetration beyond the slop
    double rhs = 0.0;
    if (impacts[k].exact) {
      rhs = impacts[k].end_offset;
    } else if (split) {
      rhs = params_.erp * (c.depth - params_.slop);
    }
    if (rhs <= 0.0) continue;
    const RigidBody& A = world.bodies()[c.a];
    const RigidBody& B = world.bodies()[c.b];
    ConstraintRow row = DirectionRow(c.a, c.b, c.point - A.x, c.point - B.x, c.normal);
    row.rhs = rhs;
    split_rows_.push_back(row);
  }
  if (split_rows_.empty()) return;
  for (SolverBody& s : bodies_) s.v.setZero(), s.w.setZero();
  PgsOptions options;
  options.iterations = params_.iterations;
  options.tolerance = 1e-9;  // m
  options.runner = &runner;
  options.measure_complementarity = false;
  split_pgs_.Solve(split_rows_, bodies_, options);
  subspace_.Solve(split_rows_, bodies_, SubspaceOptionsOf(params_, false));
  auto& bodies = world.bodies();
  runner.For(static_cast<int>(bodies.size()), kLcpBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      if (!bodies[i].IsDynamic()) continue;
      bodies[i].x += bodies_[i].v;
      bodies[i].q = (QuatFromRotationVector(bodies_[i].w) * bodies[i].q).normalized();
    }
  });
}

void LcpMethod::Solve(const World& world, std::vector<SolverBody>& bodies, ParallelRunner& runner) {
  const bool use_lemke =
      params_.solver == "lemke" && static_cast<int>(rows_.size()) <= params_.max_lemke_rows;
  if (use_lemke) {
    LemkeOptions options;
    options.max_pivots = params_.max_pivots;
    options.regularization = kLemkeRegularization;
    // Lemke's pyramid is exact along t1: turn t1 to the predicted slip
    // (lcp_contact_rows.h); a fallback solves the rows as built, as pgs does
    lemke_rows_ = rows_;
    AlignFrictionRows(contacts_, world, free_, FrictionPoints(), &lemke_rows_);
    const Status st = SolveRowsLemkeByComponent(lemke_rows_, bodies, options, &report_);
    if (st.ok() && report_.converged) {
      rows_.swap(lemke_rows_);
      return;
    }
  }
  if (params_.solver == "lemke") ++lemke_fallbacks_;
  // PGS (also as Lemke's fallback) starts from last step's impulses; joint
  // rows without one keep the joint-only solution they were built with, and
  // so do all of them where joints have damping or friction: last step's
  // impulses of a friction row are a worse start than the joints' answer
  if (params_.warm_start) {
    warm_start_.Load(contacts_, &rows_, &runner);
    if (!HasJointDynamics(world)) warm_start_.LoadJoints(joint_blocks_, 3 * contacts_.size(), &rows_);
  } else {
    for (size_t k = 3 * contacts_.size(); k < rows_.size(); ++k) rows_[k].lambda = 0.0;
  }
  // an impact row starts from the impulse of the sequential impacts, whose
  // targets it solves for (lcp_impacts.h)
  for (size_t k = 0; k < impact_impulses_.size(); ++k) {
    if (impact_impulses_[k] >= 0.0) rows_[3 * k].lambda = impact_impulses_[k];
  }
  PgsOptions options;
  options.iterations = params_.iterations;
  // one warm-started sweep a step lets an over-relaxed mode grow from step
  // to step up to the tolerance; two contract it (pgs.h, "Warm-started solves")
  options.min_iterations = std::min(2, params_.iterations);
  // lemke is chosen for exact answers: the steps it fails (degenerate
  // friction) are swept as far as the old default asked, which keeps its
  // runs where they were (docs/methods/lcp.md, "Sweeps and tolerance")
  options.tolerance = params_.solver == "lemke" ? std::min(params_.tolerance, kLemkeFallbackTolerance)
                                                : params_.tolerance;
  GroupNormalBlocks(contacts_, &Contact::normal, &pairs_);
  normal_blocks_.clear();
  for (const NormalBlock& pair : pairs_) {
    PgsNormalBlock blk;
    blk.count = pair.count;
    for (int i = 0; i < pair.count; ++i) blk.rows[i] = 3 * (pair.first + i);
    normal_blocks_.push_back(blk);
  }
  options.normal_blocks = &normal_blocks_;
  options.runner = &runner;
  options.ordered_from = static_cast<int>(3 * contacts_.size());
  // nothing in a step reads it, and the pass cost 3% of a pyramid step
  // (BENCHMARKS.md, "### lcp")
  options.measure_complementarity = false;
  report_ = pgs_.Solve(rows_, bodies, options);
  SubspaceOptions direct = SubspaceOptionsOf(params_, true);
  // the components of contacts on jointed bodies too, where the sweeps
  // stopped short (jointed_contacts.h)
  if (!joint_blocks_.empty() && !report_.converged &&
      MarkJointedContacts(contacts_, JointedComponents(joint_blocks_, bodies), &jointed_contacts_)) {
    direct.always = &jointed_contacts_;
  }
  subspace_.Solve(rows_, bodies, direct);
}

void LcpMethod::StoreWarmStart(ParallelRunner& runner) {
  // an impact's impulse is no start for the next step, which sees the
  // bodies after it: a row of touching cubes struck at one end started the
  // next step from the strike's impulses, and 20 sweeps left its bodies
  // moving at 0.02 v0; the cache keeps what a row carried beyond its impact
  // (the rows keep their whole impulse for the report)
  std::vector<double>& solved = impact_impulses_;  // no longer needed: holds the solved impulses meanwhile
  for (size_t k = 0; k < solved.size(); ++k) {
    if (solved[k] < 0.0) continue;
    const double impact = solved[k];
    solved[k] = rows_[3 * k].lambda;
    rows_[3 * k].lambda = std::max(solved[k] - impact, 0.0);
  }
  warm_start_.Store(contacts_, rows_, &runner);
  for (size_t k = 0; k < solved.size(); ++k) {
    if (solved[k] >= 0.0) rows_[3 * k].lambda = solved[k];
  }
}

StepStats LcpMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  const int count = JointSubstepCount(world, params_.joint_substep_ratio, params_.joint_substeps);
  return StepInSubsteps(world, count, ValueKind(),
                        [&](ContactSet* out) { return StepOnce(world, detector, out); }, contacts_out);
}

void LcpMethod::BuildContactRows(World& world, ParallelRunner& runner) {
  const double h = world.dt;
  ContactRowOptions row_options;
  row_options.h = h;
  row_options.restitution_threshold = params_.restitution_threshold;
  row_options.slop = params_.slop;
  row_options.baumgarte_erp = params_.drift == "baumgarte" ? params_.erp : 0.0;
  // impacts from the velocities before and after this step's forces
  LoadSolverBodies(world, runner, &before_);
  free_.resize(before_.size());
  const auto& forced = world.bodies();
  runner.For(static_cast<int>(forced.size()), kLcpBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      SolverBody& s = free_[i];
      s = before_[i];
      s.v += h * s.inv_mass * forced[i].force;
      s.w += h * (s.inv_inertia * forced[i].torque);
    }
  });
  PredictImpacts(contacts_, world, before_, free_, row_options, runner, &impacts_);
  CorrectPositions(world, contacts_, impacts_, runner);

  LoadSolverBodies(world, runner, &before_);
  if (ParsePatchTorsion(params_.patch_torsion) == PatchTorsion::kUniform) {
    PatchFrictionPoints(contacts_, &friction_points_);
  } else {
    friction_points_.clear();
  }
  WriteContactRows(contacts_, world, before_, impacts_, row_options, FrictionPoints(), runner, &rows_);
  impact_impulses_.clear();
  if (params_.impacts == "sequential") {
    SequenceImpacts(contacts_, world, before_, impacts_, params_.restitution_threshold, &sequence_, &rows_,
                    &impact_impulses_);
  }
}

namespace {

// The kinetic energy a solve added (J): per body (1/2)(v0 + v1) . dP +
// (1/2)(w0 + w1) . dL, v1 = v0 + M^-1 dP, and the kinetic energy before it.
void SolveEnergy(const World& world, const std::vector<SolverBody>& before, const std::vector<SolverBody>& after,
                 double* added, double* kinetic) {
  *added = *kinetic = 0.0;
  for (size_t i = 0; i < after.size(); ++i) {
    const RigidBody& b = world.bodies()[i];
    if (!b.IsDynamic()) continue;
    *added += 0.5 * ((before[i].v + after[i].v).dot(after[i].dP) + (before[i].w + after[i].w).dot(after[i].dL));
    *kinetic += 0.5 * (b.P.dot(before[i].v) + b.L.dot(before[i].w));
  }
}

}  // namespace

void LcpMethod::SolveWithinEnergy(const World& world, size_t first_joint_row, ParallelRunner& runner) {
  // Passive joints and contacts do no positive work, but the joint rows'
  // velocity products -(h/2) Jdot qdot (joint_rows.h) are targets, and where
  // a long chain's free end whips (w h ~ 0.25) their work lambda . rhs
  // exceeds what the step's rotation gives back: a 100-link chain of
  // growing masses gained 75 J of its 2,790 in one step. A solve that adds
  // kinetic energy is solved again without the products (docs/methods/lcp.md,
  // "Long chains"); joints with drives, damping or friction are left as they
  // are (a drive does work).
  const bool guard = first_joint_row < rows_.size() && !HasJointDynamics(world);
  if (!guard) {
    Solve(world, bodies_, runner);
    return;
  }
  energy_bodies_ = bodies_;
  energy_rows_ = rows_;
  Solve(world, bodies_, runner);
  double added = 0.0, kinetic = 0.0;
  SolveEnergy(world, energy_bodies_, bodies_, &added, &kinetic);
  if (!(added > kEnergyGuard * kinetic)) return;
  rows_.swap(energy_rows_);
  bodies_ = energy_bodies_;
  // the products at rest are zero
  for (SolverBody& b : energy_bodies_) b.v = b.w = Vec3::Zero();
  SetJointVelocityProducts(world, energy_bodies_, world.dt, joint_blocks_, &joint_rows_);
  std::copy(joint_rows_.begin(), joint_rows_.end(), rows_.begin() + first_joint_row);
  Solve(world, bodies_, runner);
}

void LcpMethod::AdvancePositions(World& world, ParallelRunner& runner) {
  // untouched bodies ballistically (x0 + v0 h + F/(2m) h^2 =
  // x0 + (v1 - F/(2m) h) h), the others with their end velocity
  const double h = world.dt;
  auto& bodies = world.bodies();
  runner.For(static_cast<int>(bodies.size()), kLcpBodyGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      RigidBody& b = bodies[i];
      const bool touched = bodies_[i].dP.squaredNorm() + bodies_[i].dL.squaredNorm() > 0.0;
      if (b.IsDynamic() && !touched) b.x -= 0.5 * h * h * b.inv_mass * b.force;
      IntegratePosition(b, h);
    }
  });
  // every iteration a Newton step: lcp's 100-link chain whose masses grow
  // tenfold runs away with chord steps (docs/methods/lcp.md)
  JointSolveOptions projection;
  projection.chord_steps = false;
  ProjectJointPositions(world, projection);
}

StepStats LcpMethod::StepOnce(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  StepStats stats;
  const double h = world.dt;
  ParallelRunner& runner = detector.runner();
  world.AccumulateForces();
  detector.Detect(world, params_.slop, h, &contacts_);
  BuildContactRows(world, runner);

  IntegrateMomenta(world, h);
  LoadSolverBodies(world, runner, &bodies_);
  // the joint rows see v* (their velocity products are taken at the
  // velocity the step ends with, see BuildJointVelocityRows)
  joint_rows_.clear();
  joint_blocks_.clear();
  BuildJointVelocityRows(world, bodies_, h, JointSolverKind::kTree, &joint_rows_, &joint_blocks_);
  // joints with damping or friction start from the joints' whole answer
  if (HasJointDynamics(world)) GuessJointImpulses(bodies_, JointSolverKind::kTree, &joint_rows_, joint_blocks_);
  const size_t first_joint_row = rows_.size();
  rows_.insert(rows_.end(), joint_rows_.begin(), joint_rows_.end());

  report_ = SolveReport();
  if (!rows_.empty()) SolveWithinEnergy(world, first_joint_row, runner);
  StoreSolverBodies(bodies_, runner, world);
  StoreWarmStart(runner);
  warm_start_.StoreJoints(joint_blocks_, first_joint_row, rows_);
  std::vector<double> lambda(joint_rows_.size()), drive_impulses;
  for (size_t k = 0; k < joint_rows_.size(); ++k) lambda[k] = rows_[first_joint_row + k].lambda;
  AddDriveImpulses(joint_blocks_, lambda, &drive_impulses);
  AddDriveEfforts(drive_impulses, h, world);
  AdvancePositions(world, runner);

  contacts_out->clear();
  for (size_t k = 0; k < contacts_.size(); ++k) {
    Contact c = contacts_[k];
    const ConstraintRow& t1 = rows_[3 * k + 1];
    const ConstraintRow& t2 = rows_[3 * k + 2];
    c.normal_value = rows_[3 * k].lambda;
    c.tangent_value = t1.lambda * t1.lin_b + t2.lambda * t2.lin_b;
    contacts_out->push_back(c);
    stats.max_penetration = std::max(stats.max_penetration, c.depth);
  }
  stats.contacts = static_cast<int>(contacts_out->size());
  stats.iterations = report_.iterations;
  stats.residual = report_.residual;
  return stats;
}

}  // namespace contactsim
