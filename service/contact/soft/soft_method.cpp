#include "service/contact/soft/soft_method.h"

#include <algorithm>

#include "service/contact/block_colours.h"
#include "service/contact/detect_ahead.h"
#include "service/contact/patch_torsion.h"
#include "service/contact/sweep_order.h"
#include "service/contact/joints/joint_solver.h"
#include "service/physics/integrator.h"

namespace contactsim {
namespace {

// bodies a thread moves ballistically at a time
constexpr int kBallisticGrain = 256;
// contacts a thread matches or reports at a time
constexpr int kContactGrain = 512;

}  // namespace

Status SoftMethod::SetParams(const ParamMap& params) {
  return SoftParamTable().Parse(Name(), params, params_, &params_);
}

Status SoftMethod::LoadState(const std::string& bytes) {
  if (warm_start_.Restore(bytes)) return Status::Ok();
  return Status::InvalidArgument("soft method state: malformed warm-start impulses (" + std::to_string(bytes.size()) +
                                 " bytes)");
}

void SoftMethod::Prepare(World& world, ParallelRunner& runner) {
  auto& bodies = world.bodies();
  in_contact_.assign(bodies.size(), 0);
  for (const Contact& c : contacts_) in_contact_[c.a] = in_contact_[c.b] = 1;
  SoftJoints::MarkJointed(world, &in_contact_);
  LoadSoftBodies(world, in_contact_, runner, &bodies_);
  if (FrictionPoints() != nullptr) PatchFrictionPoints(contacts_, &friction_points_);
  // the float path (SoftWideSolver) computes the rows and K^-1 in float
  // over its lanes; RunSubsteps fills them in should the step turn to the
  // double path after all, or restitution need them
  wide_prepare_ = params_.precision == "float" && SoftWideSolver::Applies(world, false);
  point_order_.Reset();
  PrepareSoftPoints(contacts_, world, bodies_, FrictionPoints(), Springs(world), runner, &points_, !wide_prepare_);
  // K^-1 waits for the sub-steps' colouring: the double path inverts the
  // blocks as it moves their points into the manifolds' order
  // (soft_point_order.h), the float path in float (soft_wide_kernels.h)
  BuildSoftManifolds(points_, runner, &manifolds_, /*invert=*/false);
  OrderBlocksFromTheTop(world, points_, &manifolds_, &runner);
  if (!params_.warm_start) return;
  // each chunk of contacts walks last step's pairs on its own
  // (persistent_contacts.h)
  runner.For(static_cast<int>(contacts_.size()), kContactGrain, [&](int begin, int end, int) {
    warm_start_.Match(contacts_, begin, end, [&](int k, const std::array<double, 3>& lambda) {
      points_[k].lambda_n = lambda[0];
      points_[k].lambda_t1 = lambda[1];
      points_[k].lambda_t2 = lambda[2];
    });
  });
}

SoftSprings SoftMethod::Springs(const World& world) const {
  const double h = world.dt / params_.substeps;
  // the spring must be resolved by the sub-step: at most a quarter of its rate
  const double hertz = std::min(params_.contact_hertz, 0.25 / h);
  return SoftSprings(hertz, params_.damping_ratio, h);
}

const std::vector<Vec3>* SoftMethod::FrictionPoints() const {
  return ParsePatchTorsion(params_.patch_torsion) == PatchTorsion::kUniform ? &friction_points_ : nullptr;
}

void SoftMethod::ColourManifolds() {
  roles_.resize(bodies_.size());
  for (size_t i = 0; i < bodies_.size(); ++i) {
    roles_[i] = bodies_[i].inv_mass > 0.0 ? ColourRole::kColoured : ColourRole::kFixed;
  }
  for (int k : ratio_solve_.selected()) {
    for (int i : {points_[k].a, points_[k].b}) {
      if (roles_[i] == ColourRole::kColoured) roles_[i] = ColourRole::kSerial;
    }
  }
  colours_ = ColourBlocks(points_, roles_, &manifolds_);
}

StepStats SoftMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  world.AccumulateForces();
  DetectAhead(world, detector, params_.margin, world.dt, &contacts_);
  Prepare(world, detector.runner());
  auto& bodies = world.bodies();
  detector.runner().For(static_cast<int>(bodies.size()), kBallisticGrain, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      if (!bodies_[i].substepped) AdvanceBallistic(bodies[i], world.dt);
    }
  });
  RunSubsteps(world, detector.runner());
  joints_.StoreEfforts(world);
  StoreSoftBodies(bodies_, detector.runner(), world);
  if (!world.joints().empty()) ProjectJointPositions(world);

  warm_start_.Keep(contacts_, [&](size_t k) {
    const SoftPoint& p = points_[point_order_.PointOf(static_cast<int>(k))];
    return std::array<double, 3>{p.lambda_n, p.lambda_t1, p.lambda_t2};
  });
  StepStats stats = Report(detector.runner(), contacts_out);
  world.FinishStep();
  return stats;
}

// A body resting under gravity meets its support at up to |g| dt each step
// (the sub-steps' gravity before the contact catches it); twice that keeps
// a resting contact with restitution from bouncing (the xpbd method's rule
// with the sub-step there).
double SoftMethod::RestitutionThreshold(const World& world) const {
  return std::max(params_.restitution_threshold, 2.0 * world.gravity.norm() * world.dt);
}

StepStats SoftMethod::Report(ParallelRunner& runner, ContactSet* contacts_out) {
  StepStats stats;
  stats.contacts = static_cast<int>(contacts_.size());
  stats.iterations = params_.substeps * (1 + params_.relax_iterations);
  stats.substeps = params_.substeps;
  if (!contact_report()) {
    // the next step's detection clears contacts_ before it fills it
    contacts_out->swap(contacts_);
    return stats;
  }
  contacts_out->resize(contacts_.size());
  // each contact writes its own slot; the deepest is taken after, in order
  runner.For(static_cast<int>(contacts_.size()), kContactGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      const SoftPoint& p = points_[point_order_.PointOf(k)];
      const SoftBody& A = bodies_[p.a];
      const SoftBody& B = bodies_[p.b];
      Contact& c = (*contacts_out)[k];
      c = contacts_[k];
      // the depth at the step's end, from the anchors (soft_contact.h)
      const Vec3 d = (B.dp - A.dp) + (B.dR * p.rb - A.dR * p.ra);
      c.depth = -(p.n.dot(d) + p.adjusted_separation);
      c.normal_value = p.total_n;
      c.tangent_value = p.total_t1 * p.t1 + p.total_t2 * p.t2;
    }
  });
  for (const Contact& c : *contacts_out) stats.max_penetration = std::max(stats.max_penetration, c.depth);
  return stats;
}

}  // namespace contactsim
