#include "service/contact/penalty/penalty_method.h"

#include <algorithm>

#include "service/contact/joints/joint_solver.h"
#include "service/contact/patch_torsion.h"
#include "service/contact/penalty/penalty_explicit.h"
#include "service/contact/penalty/penalty_stiffness.h"
#include "service/contact/penalty/penalty_implicit.h"
#include "service/physics/integrator.h"

namespace contactsim {

Status PenaltyMethod::SetParams(const ParamMap& params) {
  const Status refused = RefusePatchTorsion(
      Name(), params, "its friction is a spring anchored at each contact point (penalty_friction.h), not a patch's");
  if (!refused.ok()) return refused;
  return ParsePenaltyParams(Name(), params, params_, &params_);
}

ParamMap PenaltyMethod::Params() const { return PenaltyParamTable().ToMap(params_); }

std::vector<ParamDoc> PenaltyMethod::ParamDocs() const { return PenaltyParamTable().Docs(); }

std::string PenaltyMethod::SaveState() const {
  ByteWriter out;
  anchors_.Save(&out);
  return out.bytes();
}

Status PenaltyMethod::LoadState(const std::string& bytes) {
  if (bytes.empty()) {  // saved by a run without anchors, or before any contact
    anchors_.Clear();
    return Status::Ok();
  }
  FrictionAnchors loaded;
  ByteReader in(bytes);
  if (!loaded.Load(&in) || !in.done()) {
    return Status::InvalidArgument("penalty method state: malformed friction anchors (" +
                                   std::to_string(bytes.size()) + " bytes)");
  }
  anchors_ = std::move(loaded);
  return Status::Ok();
}

void PenaltyMethod::ExplicitWorldStep(World& world, CollisionDetector& detector, StepStats* stats) {
  const double dt = world.dt;
  detector.Detect(world, SpeculativeMargin(world, params_.margin, dt), dt, &contacts_);
  RowOptions options;
  options.speculative = true;
  options.elapsed = dt;
  BuildPenaltyRows(world, contacts_, params_, anchors_, options, &rows_);
  if (params_.preload == "placed") {
    preload_.Apply(world, params_, PenaltyImpactThreshold(world, params_.impact_threshold), &rows_);
  }
  const int substeps = ExplicitSubsteps(world, rows_, params_, dt);
  const ExplicitStats s = ExplicitStep(world, rows_, params_, dt, substeps, &impacts_);
  stats->substeps = s.substeps;
  stats->max_penetration = s.max_penetration;
  KeepAnchors(world, contacts_, dt);
}

void PenaltyMethod::ImplicitSubstep(World& world, double h, StepStats* stats) {
  auto& bodies = world.bodies();
  std::vector<Vec3> P0(bodies.size()), L0(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) P0[i] = bodies[i].P, L0[i] = bodies[i].L;
  const double theta = params_.theta;
  const ImplicitStats s = ImplicitMomentumStep(world, rows_, h, theta, params_.iterations);
  stats->iterations += s.iterations;
  stats->residual = std::max(stats->residual, s.residual);
  SolveJointVelocities(world, h);  // on the new momenta, before the positions use them
  // positions with the theta-weighted velocity (exact ballistic flight for
  // theta = 1/2): move with the blended momenta, then keep the new ones
  std::vector<Vec3> P1(bodies.size()), L1(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    P1[i] = bodies[i].P;
    L1[i] = bodies[i].L;
    bodies[i].P = (1.0 - theta) * P0[i] + theta * P1[i];
    bodies[i].L = (1.0 - theta) * L0[i] + theta * L1[i];
  }
  IntegratePositions(world, h);
  for (size_t i = 0; i < bodies.size(); ++i) bodies[i].P = P1[i], bodies[i].L = L1[i];
}

void PenaltyMethod::KeepAnchors(const World& world, const ContactSet& contacts, double h) {
  const bool implicit = params_.integrator == "implicit";
  for (const PenaltyRow& row : rows_) {
    // a placed overlap not yet pushed out is kept while it lasts, even with
    // its spring slack
    const bool placed = row.anchor.rest_depth > 0.0 && row.depth > 0.0;
    if (!row.engaged || (row.lambda <= 0.0 && !placed)) continue;
    AnchorState next = row.anchor;
    if (row.mu <= 0.0) {
      next.stretch.setZero();  // no friction: nothing to anchor
    } else if (!implicit) {
      // the explicit step advanced the stretch by each sub-step's slip
    } else if (row.sliding) {
      // the anchor slid so that the spring alone carries mu lambda
      next.stretch = -row.ft / row.kt;
    } else {
      // the slip over the step, at the velocity the positions moved with
      Vec3 v = RelativeVelocity(world, row);
      v = (1.0 - params_.theta) * (row.vt0 + row.n * row.vn0) + params_.theta * v;
      next.stretch += h * (v - row.n * row.n.dot(v));
    }
    anchors_.Keep(contacts[row.contact], next);
  }
  anchors_.Commit();
}

StepStats PenaltyMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  const int count = JointSubstepCount(world, params_.joint_substep_ratio, params_.joint_substeps);
  return StepInSubsteps(world, count, ValueKind(),
                        [&](ContactSet* out) { return StepOnce(world, detector, out); }, contacts_out);
}

StepStats PenaltyMethod::StepOnce(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  StepStats stats;
  contacts_out->clear();
  world.AccumulateForces();
  if (params_.integrator == "implicit") {
    ImplicitWorldStep(world, detector, &stats);
  } else {
    ExplicitWorldStep(world, detector, &stats);
  }
  for (const PenaltyRow& row : rows_) {
    if (!row.engaged) continue;
    const Contact& c = contacts_[row.contact];
    if (row.depth <= 0.0 && row.lambda <= 0.0 && row.impulse <= 0.0) continue;
    Contact out = c;
    out.depth = row.depth;
    // an impact's impulse as the mean force over the step
    out.normal_value = row.lambda + row.impulse / world.dt;
    out.tangent_value = row.ft;
    contacts_out->push_back(out);
  }
  stats.contacts = static_cast<int>(contacts_out->size());
  return stats;
}

void PenaltyMethod::ImplicitWorldStep(World& world, CollisionDetector& detector, StepStats* stats) {
  const double h = world.dt / params_.substeps;
  auto& bodies = world.bodies();
  std::vector<Vec3> force(bodies.size()), torque(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) force[i] = bodies[i].force, torque[i] = bodies[i].torque;
  RowOptions options;
  options.h = h;
  options.implicit = true;
  options.theta = params_.theta;
  options.elapsed = h;
  for (int sub = 0; sub < params_.substeps; ++sub) {
    for (size_t i = 0; i < bodies.size(); ++i) bodies[i].force = force[i], bodies[i].torque = torque[i];
    detector.Detect(world, params_.margin, h, &contacts_);
    BuildPenaltyRows(world, contacts_, params_, anchors_, options, &rows_);
    for (const Contact& c : contacts_) stats->max_penetration = std::max(stats->max_penetration, c.depth);
    ImplicitSubstep(world, h, stats);
    KeepAnchors(world, contacts_, h);
    ProjectJointPositions(world);
  }
  // the external wrench stays the accumulated one, as for other methods
  for (size_t i = 0; i < bodies.size(); ++i) bodies[i].force = force[i], bodies[i].torque = torque[i];
  stats->substeps = params_.substeps;
}

}  // namespace contactsim
