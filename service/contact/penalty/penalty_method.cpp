#include "service/contact/penalty/penalty_method.h"

#include <algorithm>

#include "service/contact/joints/joint_solver.h"
#include "service/contact/penalty/penalty_implicit.h"
#include "service/physics/integrator.h"

namespace contactsim {

Status PenaltyMethod::SetParams(const ParamMap& params) {
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

void PenaltyMethod::ExplicitSubstep(World& world, double h) {
  auto& bodies = world.bodies();
  for (PenaltyRow& row : rows_) {
    if (!row.engaged) continue;
    // each dashpot integrated implicitly against its point's effective
    // mass: c / (1 + h c K) (see the header)
    const double cn = row.law.c / (1.0 + h * row.law.c * row.inv_mass_n);
    const double ct = row.ct / (1.0 + h * row.ct * row.inv_mass_t);
    row.lambda = std::max(0.0, row.law.lambda0 + (row.law.c - cn) * row.vn0);
    // the anchor slides when the trial force leaves the Coulomb disk, so
    // that the spring alone carries the limited force
    const Vec3 trial = -row.kt * row.anchor.stretch - ct * row.vt0;
    row.ft = CoulombLimit(trial, row.mu * row.lambda, &row.sliding);
    if (row.sliding) row.anchor.stretch = -row.ft / row.kt;
    const Vec3 f = row.lambda * row.n + row.ft;  // on B; -f on A
    if (bodies[row.b].IsDynamic()) {
      bodies[row.b].force += f;
      bodies[row.b].torque += row.rb.cross(f);
    }
    if (bodies[row.a].IsDynamic()) {
      bodies[row.a].force -= f;
      bodies[row.a].torque -= row.ra.cross(f);
    }
  }
  IntegrateMomenta(world, h);
  SolveJointVelocities(world, h);
  IntegratePositions(world, h);
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
  for (const PenaltyRow& row : rows_) {
    if (!row.engaged || row.lambda <= 0.0) continue;
    AnchorState next = row.anchor;
    const bool implicit = params_.integrator == "implicit";
    if (row.mu <= 0.0) {
      next.stretch.setZero();  // no friction: nothing to anchor
    } else if (implicit && row.sliding) {
      // the anchor slid so that the spring alone carries mu lambda
      next.stretch = -row.ft / row.kt;
    } else {
      // the slip over the step, at the velocity the positions moved with
      // (explicit: the end velocity; a slide already reset the anchor)
      Vec3 v = RelativeVelocity(world, row);
      if (implicit) v = (1.0 - params_.theta) * (row.vt0 + row.n * row.vn0) + params_.theta * v;
      next.stretch += h * (v - row.n * row.n.dot(v));
    }
    anchors_.Keep(contacts[row.contact], next);
  }
  anchors_.Commit();
}

StepStats PenaltyMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  StepStats stats;
  contacts_out->clear();
  const bool implicit = params_.integrator == "implicit";
  const double h = world.dt / params_.substeps;
  world.AccumulateForces();
  auto& bodies = world.bodies();
  std::vector<Vec3> force(bodies.size()), torque(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) force[i] = bodies[i].force, torque[i] = bodies[i].torque;

  RowOptions options;
  options.h = h;
  options.implicit = implicit;
  options.theta = params_.theta;
  for (int sub = 0; sub < params_.substeps; ++sub) {
    for (size_t i = 0; i < bodies.size(); ++i) bodies[i].force = force[i], bodies[i].torque = torque[i];
    detector.Detect(world, params_.margin, h, &contacts_);
    BuildPenaltyRows(world, contacts_, params_, anchors_, options, &rows_);
    for (const Contact& c : contacts_) stats.max_penetration = std::max(stats.max_penetration, c.depth);
    if (implicit) {
      ImplicitSubstep(world, h, &stats);
    } else {
      ExplicitSubstep(world, h);
    }
    KeepAnchors(world, contacts_, h);
    ProjectJointPositions(world);
  }
  // the external wrench stays the accumulated one, as for other methods
  for (size_t i = 0; i < bodies.size(); ++i) bodies[i].force = force[i], bodies[i].torque = torque[i];
  for (const PenaltyRow& row : rows_) {
    const Contact& c = contacts_[row.contact];
    if (c.depth <= 0.0 && row.lambda <= 0.0) continue;
    Contact out = c;
    out.normal_value = row.lambda;
    out.tangent_value = row.ft;
    contacts_out->push_back(out);
  }
  world.FinishStep();
  stats.substeps = params_.substeps;
  stats.contacts = static_cast<int>(contacts_out->size());
  return stats;
}

}  // namespace contactsim
