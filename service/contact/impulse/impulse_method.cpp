#include "service/contact/impulse/impulse_method.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "service/collision/depth_bound.h"
#include "service/collision/motion_bound.h"
#include "service/collision/narrowphase.h"
#include "service/collision/time_of_impact.h"
#include "service/contact/joints/joint_solver.h"
#include "service/contact/jointed_contacts.h"
#include "service/contact/patch_torsion.h"
#include "service/contact/slip_friction_step.h"
#include "service/physics/byte_stream.h"
#include "service/physics/integrator.h"

namespace contactsim {
namespace {

// Indices a thread takes at a time in the step's per-row, per-block,
// per-pair and per-body loops: enough work to pay for the atomic counter.
constexpr int kRowGrain = 256;
constexpr int kImpulseBlockGrain = 128;
constexpr int kImpulsePairGrain = 64;
constexpr int kImpulseBodyGrain = 64;
// impact pairs a thread advances and collides at a time in the impact
// time's search (two body copies, two advances and a narrowphase call each)
constexpr int kImpactGrain = 8;

}  // namespace

Status ImpulseMethod::SetParams(const ParamMap& params) {
  return ImpulseParamTable().Parse(Name(), params, params_, &params_);
}

std::string ImpulseMethod::SaveState() const { return warm_.Save(); }

Status ImpulseMethod::LoadState(const std::string& bytes) {
  if (warm_.Restore(bytes)) return Status::Ok();
  return Status::InvalidArgument("impulse method state: malformed warm-start forces (" + std::to_string(bytes.size()) +
                                 " bytes)");
}

// Split impulse: pseudo-velocities solved like contact impulses for a
// separation of beta (depth - slop) each, then applied to positions only.
void ImpulseMethod::CorrectPositions(World& world, const ContactSet& contacts) {
  if (params_.position_correction <= 0.0) return;
  LoadSolverBodies(world, *runner_, &solver_);
  // a row per contact deeper than the slop, in contact order: each
  // contact's row index counted here, the rows made on the threads
  const int n = static_cast<int>(contacts.size());
  row_of_.resize(n);
  int count = 0;
  for (int k = 0; k < n; ++k) row_of_[k] = contacts[k].depth - params_.slop > 0.0 ? count++ : -1;
  split_rows_.resize(count);
  std::vector<double> target(count);
  runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) {
      if (row_of_[k] < 0) continue;
      split_rows_[row_of_[k]] = MakeContactRow(contacts[k], world, solver_);
      target[row_of_[k]] = params_.position_correction * (contacts[k].depth - params_.slop);
    }
  });
  if (split_rows_.empty()) return;
  for (SolverBody& s : solver_) s.v.setZero(), s.w.setZero();
  SetColourRoles(world);
  SweepPositions(target);
  SolveMassRatios(split_rows_, &target);
  DisplaceBodies(solver_, *runner_, world);
}

void ImpulseMethod::SolveMassRatios(std::vector<ContactRow>& rows, const std::vector<double>* target, bool joints) {
  SubspaceOptions options;
  options.mass_ratio = params_.direct_mass_ratio;
  options.max_rows = params_.direct_max_rows;
  options.energy_guard = target == nullptr;  // targets: the split impulse's pseudo-velocities
  joints = joints && MarkJointedContacts(rows, solver_.size(), [this](int i) { return joints_.Jointed(i); },
                                         &jointed_contacts_);
  if (joints) options.always = &jointed_contacts_;
  if (rows.empty() || (!joints && !SubspaceSolver::MassRatioReached(solver_, options.mass_ratio))) return;
  // per contact a row along n with the accumulated impulse the bodies carry,
  // and in the contact phase (no targets) the two friction rows
  const int per = target ? 1 : 3;
  normal_rows_.assign(per * rows.size(), ConstraintRow());
  for (size_t k = 0; k < rows.size(); ++k) {
    const ContactRow& c = rows[k];
    const Vec3 dirs[3] = {c.n, c.t1, c.t2};
    const double lambdas[3] = {c.lambda_n, c.lambda_t1, c.lambda_t2};
    for (int d = 0; d < per; ++d) {
      ConstraintRow& r = normal_rows_[per * k + d];
      r.a = c.a;
      r.b = c.b;
      r.lin_a = -dirs[d];
      r.ang_a = -(d == 0 ? c.ra : c.fa).cross(dirs[d]);
      r.lin_b = dirs[d];
      r.ang_b = (d == 0 ? c.rb : c.fb).cross(dirs[d]);
      r.lambda = lambdas[d];
      if (d == 0) {
        r.lo = 0.0;
        r.rhs = target ? (*target)[k] : 0.0;
      } else {
        r.normal_row = static_cast<int>(per * k);
        r.mu = c.friction;
      }
    }
  }
  const size_t first_joint_row = normal_rows_.size();
  if (joints) joints_.AppendRows(&normal_rows_);
  subspace_.Solve(normal_rows_, solver_, options);
  if (joints) joints_.ReadImpulses(normal_rows_, first_joint_row);
  for (size_t k = 0; k < rows.size(); ++k) {
    rows[k].lambda_n = normal_rows_[per * k].lambda;
    if (per == 1) continue;
    rows[k].lambda_t1 = normal_rows_[per * k + 1].lambda;
    rows[k].lambda_t2 = normal_rows_[per * k + 2].lambda;
  }
}

void ImpulseMethod::BuildNormalBlocks(const std::vector<ContactRow>& rows) {
  GroupNormalBlocks(rows, &ContactRow::n, &blocks_);
  runner_->For(static_cast<int>(blocks_.size()), kImpulseBlockGrain, [&](int begin, int end, int /*worker*/) {
    for (int b = begin; b < end; ++b) {
      NormalBlock& m = blocks_[b];
      if (m.count < 2) continue;
      const ContactRow& r0 = rows[m.first];
      NormalBlockPoint points[kMaxNormalBlock];
      bool one_normal = true;
      for (int i = 0; i < m.count; ++i) {
        const ContactRow& row = rows[m.first + i];
        const AngularResponse& r = responses_[m.first + i];
        one_normal = one_normal && row.n.dot(r0.n) >= 1.0 - 1e-9;
        points[i] = {row.ra, r.ra_n, r.rb_n, r.a_n, r.b_n};
      }
      const double k_lin = solver_[r0.a].inv_mass + solver_[r0.b].inv_mass;
      m.block = one_normal && InvertNormalBlock(points, m.count, k_lin, r0.t1, r0.t2, &m.inv_k);
    }
  });
}

bool ImpulseMethod::NormalBlockStep(const NormalBlock& m, const std::vector<ContactRow>& rows,
                                    Eigen::Vector4d* step) const {
  Eigen::Vector4d vn = Eigen::Vector4d::Zero();
  for (int i = 0; i < m.count; ++i) {
    const ContactRow& row = rows[m.first + i];
    const AngularResponse& r = responses_[m.first + i];
    vn[i] = NormalVelocity(row, r);
  }
  *step = m.inv_k * vn;
  for (int i = 0; i < m.count; ++i) {
    if (rows[m.first + i].lambda_n - (*step)[i] < 0.0) return false;
  }
  return true;
}

double ImpulseMethod::SweepBlock(const NormalBlock& m, std::vector<ContactRow>& rows) {
  auto normal = [&](ContactRow& row, const AngularResponse& r, double dn) {
    row.lambda_n += dn;
    PushNormal(row, r, dn);
    return std::abs(dn) * row.k_n;
  };
  double worst = 0.0;  // largest change of a relative velocity, m/s
  // friction first, limited by the normal impulse of the last sweep
  for (int k = m.first; k < m.first + m.count; ++k) {
    ContactRow& row = rows[k];
    const AngularResponse& r = responses_[k];
    const SolverBody& A = solver_[row.a];
    const SolverBody& B = solver_[row.b];
    const double old1 = row.lambda_t1, old2 = row.lambda_t2;
    double l1 = old1, l2 = old2;
    SlipFrictionStep(row.friction * row.lambda_n, RowVelocity(A, B, row.t1, r.fa_t1, r.fb_t1),
                     RowVelocity(A, B, row.t2, r.fa_t2, r.fb_t2), row.mass_t1, row.mass_t2, row.k_t12, &l1, &l2);
    row.lambda_t1 = l1;
    row.lambda_t2 = l2;
    const double d1 = l1 - old1, d2 = l2 - old2;
    const Vec3 dJt = d1 * row.t1 + d2 * row.t2;
    Push(row, dJt, d1 * r.a_t1 + d2 * r.a_t2, d1 * r.b_t1 + d2 * r.b_t2, d1 * r.fa_t1 + d2 * r.fa_t2,
          d1 * r.fb_t1 + d2 * r.fb_t2);
    worst = std::max(worst, dJt.norm() * row.k_n);
  }
  // then the normal rows: together where the block keeps every impulse >= 0
  Eigen::Vector4d step;
  if (m.block && NormalBlockStep(m, rows, &step)) {
    for (int i = 0; i < m.count; ++i) {
      worst = std::max(worst, normal(rows[m.first + i], responses_[m.first + i], -step[i]));
    }
    return worst;
  }
  for (int k = m.first; k < m.first + m.count; ++k) {
    ContactRow& row = rows[k];
    const AngularResponse& r = responses_[k];
    const double next = std::max(0.0, row.lambda_n - NormalVelocity(row, r) * row.mass_n);
    worst = std::max(worst, normal(row, r, next - row.lambda_n));
  }
  return worst;
}

void ImpulseMethod::LoadWarmStart(const ContactSet& contacts, double h, std::vector<ContactRow>& rows) {
  runner_->For(static_cast<int>(rows.size()), kRowGrain, [&](int begin, int end, int /*worker*/) {
    size_t hint = 0;  // the cache's search hint, this thread's own
    for (int k = begin; k < end; ++k) {
      ContactRow& row = rows[k];
      row.lambda_n = row.lambda_t1 = row.lambda_t2 = 0.0;
      if (!params_.warm_start) continue;
      const Contact& c = contacts[k];
      const std::array<double, 3>* warm = warm_.Find(c, &hint);
      if (warm == nullptr) continue;
      // the stored tangent force projected on this step's tangent basis,
      // kept in the Coulomb disk of the warm normal impulse
      Vec3 t1f, t2f;
      PerpendicularBasis(c.normal, &t1f, &t2f);
      const Vec3 tangent = (*warm)[1] * t1f + (*warm)[2] * t2f;
      row.lambda_n = h * (*warm)[0];
      row.lambda_t1 = h * tangent.dot(row.t1);
      row.lambda_t2 = h * tangent.dot(row.t2);
      const double norm = std::hypot(row.lambda_t1, row.lambda_t2);
      const double limit = row.friction * row.lambda_n;
      if (norm > limit) {
        const double scale = norm > 0.0 ? limit / norm : 0.0;
        row.lambda_t1 *= scale;
        row.lambda_t2 *= scale;
      }
    }
  });
}

void ImpulseMethod::FindResponses(const std::vector<ContactRow>& rows) {
  const int n = static_cast<int>(rows.size());
  responses_.resize(n);
  runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) {
      const ContactRow& row = rows[k];
      const Mat3& Ia = solver_[row.a].inv_inertia;
      const Mat3& Ib = solver_[row.b].inv_inertia;
      AngularResponse& r = responses_[k];
      r.ra_n = row.ra.cross(row.n);
      r.fa_t1 = row.fa.cross(row.t1);
      r.fa_t2 = row.fa.cross(row.t2);
      r.rb_n = row.rb.cross(row.n);
      r.fb_t1 = row.fb.cross(row.t1);
      r.fb_t2 = row.fb.cross(row.t2);
      r.a_n = Ia * r.ra_n;
      r.a_t1 = Ia * r.fa_t1;
      r.a_t2 = Ia * r.fa_t2;
      r.b_n = Ib * r.rb_n;
      r.b_t1 = Ib * r.fb_t1;
      r.b_t2 = Ib * r.fb_t2;
    }
  });
}

int ImpulseMethod::ContactPhase(const World& world, const ContactSet& contacts, double h, int sweeps,
                                std::vector<ContactRow>& rows, bool* converged) {
  // Accumulated impulses start from last step's forces times h (or zero);
  // the collision phase's impulses are kept apart (collision_n) so that
  // clamping applies to this phase only.
  const int n = static_cast<int>(rows.size());
  std::vector<double> collision_n(n);
  std::vector<Vec3> collision_t(n);
  for (int k = 0; k < n; ++k) {
    collision_n[k] = rows[k].lambda_n;
    collision_t[k] = rows[k].lambda_t1 * rows[k].t1 + rows[k].lambda_t2 * rows[k].t2;
  }
  LoadWarmStart(contacts, h, rows);
  BuildNormalBlocks(rows);
  bool interleave = false;
  const int it = SweepContacts(world, h, sweeps, rows, converged, &interleave);
  // jointed components too, where the sweeps stopped short (jointed_contacts.h)
  SolveMassRatios(rows, nullptr, interleave && !*converged);
  // the last joint solve with its velocity products taken at the velocities
  // the sweeps leave: the contacts of a fast-folding chain change them too
  // much for the products taken before (a 100-link chain blew up); the
  // damping and drive rows keep what the sweeps' joint solves applied
  joints_.Rebuild(world, solver_, h);
  joints_.Solve(solver_);
  warm_forces_.resize(n);
  runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) {
      ContactRow& row = rows[k];
      Vec3 t1f, t2f;
      PerpendicularBasis(contacts[k].normal, &t1f, &t2f);
      const Vec3 tangent = (row.lambda_t1 * row.t1 + row.lambda_t2 * row.t2) / h;
      warm_forces_[k] = {row.lambda_n / h, tangent.dot(t1f), tangent.dot(t2f)};
      row.lambda_n += collision_n[k];
      row.lambda_t1 += collision_t[k].dot(row.t1);
      row.lambda_t2 += collision_t[k].dot(row.t2);
    }
  });
  return it;
}

void ImpulseMethod::FindTouching(const ContactSet& contacts) {
  // the detector emits a pair's contacts together and the pairs in body
  // order, so the list comes out sorted and the sort is a check; a stable
  // sort otherwise keeps each pair's contacts in their order, so the
  // deepest is taken in the same order either way
  const int n = static_cast<int>(contacts.size());
  touching_points_.resize(n);
  runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) {
      const Contact& c = contacts[k];
      touching_points_[k] = {
          {std::min(c.a, c.b), std::max(c.a, c.b)}, c.depth, c.a < c.b ? c.normal : Vec3(-c.normal)};
    }
  });
  const auto by_pair = [](const Touching& l, const Touching& r) { return l.pair < r.pair; };
  if (!std::is_sorted(touching_points_.begin(), touching_points_.end(), by_pair)) {
    std::stable_sort(touching_points_.begin(), touching_points_.end(), by_pair);
  }
  // each pair's deepest point (the first of equal depths), the pairs found
  // by the runs of kRowGrain points they start in: counted, then written
  // to their places, each run on any thread
  const auto starts = [&](int k) { return k == 0 || touching_points_[k - 1].pair != touching_points_[k].pair; };
  const int runs = (n + kRowGrain - 1) / kRowGrain;
  touching_offsets_.assign(runs + 1, 0);
  runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) touching_offsets_[k / kRowGrain + 1] += starts(k) ? 1 : 0;
  });
  for (int r = 0; r < runs; ++r) touching_offsets_[r + 1] += touching_offsets_[r];
  touching_.resize(touching_offsets_[runs]);
  runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
    int out = touching_offsets_[begin / kRowGrain];
    for (int k = begin; k < end; ++k) {
      if (!starts(k)) continue;
      Touching deepest = touching_points_[k];
      for (int i = k + 1; i < n && touching_points_[i].pair == deepest.pair; ++i) {
        if (touching_points_[i].depth > deepest.depth) deepest = touching_points_[i];
      }
      touching_[out++] = deepest;
    }
  });
}

std::vector<ImpulseMethod::Impact> ImpulseMethod::FindImpacts(const std::vector<RigidBody>& bodies,
                                                              const ContactSet& contacts, CollisionDetector& detector,
                                                              double h) {
  const double margin = params_.slop;
  FindTouching(contacts);
  // each pair writes its own slot, gathered in pair order below
  const std::vector<BodyPair>& pairs = detector.pairs();
  const int n = static_cast<int>(pairs.size());
  impact_depth_.assign(n, std::numeric_limits<double>::quiet_NaN());
  impact_scratch_.resize(runner_->threads());
  runner_->For(n, kImpulsePairGrain, [&](int begin, int end, int worker) {
    ContactSet& scratch = impact_scratch_[worker];
    for (int i = begin; i < end; ++i) {
      const BodyPair& p = pairs[i];
      // A touching pair's contact rows hold only the points found at the
      // start: a box struck while resting on one corner turns another corner
      // into the ground (a 0.1 kg box under a falling 3 kg sphere went 45 mm
      // deep in one step). It is an impact when any point goes a margin
      // deeper than the pair started, and cannot be when the pair's motion
      // could not close a margin in h.
      const auto was = std::lower_bound(touching_.begin(), touching_.end(), p,
                                        [](const Touching& t, const BodyPair& q) { return t.pair < q; });
      const bool apart = was == touching_.end() || was->pair != p;
      if (!apart && ClosingSpeedBound(bodies[p.first], bodies[p.second], h) * h <= margin) continue;
      const double start = apart ? 0.0 : std::max(0.0, was->depth);
      // nor when the pair overlaps along its deepest start contact's normal
      // by too little for any contact to be that deep (depth_bound.h): the
      // same answer as the full test for a look along one axis
      if (!apart && ContactDepthBound(bodies[p.first], bodies[p.second], was->normal) <= start + margin) continue;
      scratch.clear();
      // a pair the detection found apart is usually still apart along the
      // axis it stored (separating_axis_cache.h), which answers in one axis
      detector.narrowphase().CollideReadOnly(bodies[p.first], p.first, bodies[p.second], p.second, 0.0, &scratch);
      for (const Contact& c : scratch) {
        if (c.depth > start + margin) {
          // the search stops at touching, or half a margin past a touching pair's start
          impact_depth_[i] = apart ? 0.0 : start + 0.5 * margin;
          break;
        }
      }
    }
  });
  std::vector<Impact> impacts;
  for (int i = 0; i < n; ++i) {
    if (!std::isnan(impact_depth_[i])) impacts.push_back({pairs[i].first, pairs[i].second, impact_depth_[i]});
  }
  return impacts;
}

double ImpulseMethod::FindImpactTime(const std::vector<RigidBody>& start, const std::vector<Impact>& impacts, double h,
                                     int* iterations) {
  // Bound on how fast any pair can close during the sub-step (needed for
  // conservative advancement, which keeps thin bodies from being skipped):
  // relative speed plus rotation sweep plus what the forces add over h.
  double max_closing = 0.0;
  for (const Impact& p : impacts) {
    max_closing = std::max(max_closing, ClosingSpeedBound(start[p.a], start[p.b], h));
  }
  // Separations up to everything the sub-step can close are measured exactly
  // rather than clamped, so advancement takes full-size steps.
  const double reach = max_closing * h + 2.0 * params_.slop;
  // the pairs on the threads, each worker keeping its own deepest: a
  // maximum is the same whichever pairs each took (impact_scratch_ is
  // FindImpacts', sized to the threads)
  impact_deepest_.resize(runner_->threads());
  auto distance_at = [&](double t) {
    std::fill(impact_deepest_.begin(), impact_deepest_.end(), -reach);  // the most a pair is past its impact depth
    runner_->For(static_cast<int>(impacts.size()), kImpactGrain, [&](int begin, int end, int worker) {
      ContactSet& scratch = impact_scratch_[worker];
      double& deepest = impact_deepest_[worker];
      for (int i = begin; i < end; ++i) {
        const Impact& p = impacts[i];
        RigidBody a = start[p.a];
        RigidBody b = start[p.b];
        AdvanceBallistic(a, t);
        AdvanceBallistic(b, t);
        scratch.clear();
        Collide(a, p.a, b, p.b, reach, &scratch);
        for (const Contact& c : scratch) deepest = std::max(deepest, c.depth - p.depth);
      }
    });
    return -*std::max_element(impact_deepest_.begin(), impact_deepest_.end());
  };
  TimeOfImpactOptions options;
  ParseRootFinder(params_.toi, &options.finder);
  options.tolerance = 0.25 * params_.slop;
  options.max_closing_speed = max_closing;
  const TimeOfImpactResult result = FindTimeOfImpact(distance_at, 0.0, h, options);
  *iterations += result.evaluations;
  return result.hit ? result.time : h;
}

StepStats ImpulseMethod::Step(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  const int count = JointSubstepCount(world, params_.joint_substep_ratio, params_.joint_substeps);
  return StepInSubsteps(world, count, ValueKind(),
                        [&](ContactSet* out) { return StepOnce(world, detector, out); }, contacts_out);
}

void ImpulseMethod::CopyBodies(const std::vector<RigidBody>& from, std::vector<RigidBody>* to) const {
  to->resize(from.size());
  runner_->For(static_cast<int>(from.size()), kImpulseBodyGrain, [&](int begin, int end, int /*worker*/) {
    std::copy(from.begin() + begin, from.begin() + end, to->begin() + begin);
  });
}

void ImpulseMethod::MoveBodies(double h, World& world) {
  auto& bodies = world.bodies();
  runner_->For(static_cast<int>(bodies.size()), kImpulseBodyGrain, [&](int begin, int end, int /*worker*/) {
    for (int i = begin; i < end; ++i) {
      RigidBody& b = bodies[i];
      if (b.motion == MotionType::kStatic) continue;
      const bool touched = solver_[i].dP.squaredNorm() + solver_[i].dL.squaredNorm() > 0.0;
      // ballistic: v0 h + F/(2m) h^2 with v0 = v - F/m h
      const Vec3 v = touched || !b.IsDynamic() ? b.LinearVelocity()
                                               : Vec3(b.LinearVelocity() - 0.5 * h * b.inv_mass * b.force);
      b.x += v * h;
      // dynamic bodies turn by the midpoint rule with L held (integrator.h),
      // which keeps a free body's |L| and energy; exp(w h) drifted 1.5% in 10 s
      b.q = b.IsDynamic() ? MidpointRotation(b.q, b.L, b.inv_inertia_body, h)
                          : Quat((QuatFromRotationVector(b.AngularVelocity() * h) * b.q).normalized());
    }
  });
}

int ImpulseMethod::SweepAndMove(World& world, const ContactSet& contacts, double h, int sweeps, bool* converged) {
  IntegrateMomenta(world, h);
  LoadSolverBodies(world, *runner_, &solver_);
  const int it = ContactPhase(world, contacts, h, sweeps, rows_, converged);
  StoreSolverBodies(solver_, *runner_, world);
  MoveBodies(h, world);
  return it;
}

double ImpulseMethod::ImpactTime(const std::vector<RigidBody>& bodies, const ContactSet& contacts,
                                 CollisionDetector& detector, double h, int* iterations) {
  const std::vector<Impact> impacts = FindImpacts(bodies, contacts, detector, h);
  if (impacts.empty()) return h;
  // h when the overlap was there from the start: it is left to the correction
  return FindImpactTime(start_bodies_, impacts, h, iterations);
}

StepStats ImpulseMethod::StepOnce(World& world, CollisionDetector& detector, ContactSet* contacts_out) {
  StepStats stats;
  runner_ = &detector.runner();
  contacts_out->clear();
  const double margin = params_.slop;
  double remaining = world.dt;
  world.AccumulateForces();
  ContactSet contacts;
  detector.Detect(world, margin, remaining, &contacts);
  CorrectPositions(world, contacts);

  for (int sub = 0;; ++sub) {
    if (sub > 0) detector.Detect(world, margin, remaining, &contacts);
    LoadSolverBodies(world, *runner_, &solver_);
    SetColourRoles(world);
    const int n = static_cast<int>(contacts.size());
    rows_.resize(n);
    const bool torsion = ParsePatchTorsion(params_.patch_torsion) == PatchTorsion::kUniform;
    if (torsion) PatchFrictionPoints(contacts, &friction_points_);
    runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
      for (int k = begin; k < end; ++k) {
        rows_[k] = MakeContactRow(contacts[k], world, solver_, torsion ? &friction_points_[k] : nullptr);
      }
    });
    FindResponses(rows_);
    stats.iterations += CollisionPhase(rows_);
    StoreSolverBodies(solver_, *runner_, world);
    CopyBodies(world.bodies(), &start_bodies_);

    const bool last = params_.toi == "off" || sub + 1 >= params_.max_substeps;
    // A sub-step that ends in an impact is thrown away but for the pairs it
    // finds and its warm-start forces: its contact phase may stop short
    // (impact_sweeps), and a sub-step found free of impacts is swept again
    // in full from its start (docs/methods/impulse.md, "Sweeps before the
    // impact check").
    const bool trial = sub > 0 && !last && params_.impact_sweeps > 0 && params_.impact_sweeps < params_.iterations;
    if (trial) collision_rows_ = rows_;
    bool converged = false;
    stats.iterations +=
        SweepAndMove(world, contacts, remaining, trial ? params_.impact_sweeps : params_.iterations, &converged);
    auto& bodies = world.bodies();
    double t_c = last ? remaining : ImpactTime(bodies, contacts, detector, remaining, &stats.iterations);
    // sweeps that met the tolerance in the trial are the full phase's, bit for bit
    if (trial && !converged && t_c >= remaining) {
      CopyBodies(start_bodies_, &bodies);
      rows_ = collision_rows_;
      stats.iterations += SweepAndMove(world, contacts, remaining, params_.iterations, &converged);
      t_c = ImpactTime(bodies, contacts, detector, remaining, &stats.iterations);
    }
    warm_.StoreFrame(contacts, warm_forces_, runner_);  // keeps the points with a normal force
    if (t_c >= remaining) {
      contacts_out->assign(contacts.begin(), contacts.end());
      runner_->For(n, kRowGrain, [&](int begin, int end, int /*worker*/) {
        for (int k = begin; k < end; ++k) {
          Contact& c = (*contacts_out)[k];
          c.normal_value = rows_[k].lambda_n;
          c.tangent_value = rows_[k].lambda_t1 * rows_[k].t1 + rows_[k].lambda_t2 * rows_[k].t2;
        }
      });
      break;
    }
    CopyBodies(start_bodies_, &bodies);
    runner_->For(static_cast<int>(bodies.size()), kImpulseBodyGrain, [&](int begin, int end, int /*worker*/) {
      for (int i = begin; i < end; ++i) AdvanceBallistic(bodies[i], t_c);
    });
    remaining -= t_c;
    ++stats.substeps;
  }
  std::vector<double> drive_impulses;  // the last contact phase's, over `remaining`
  joints_.AddDriveImpulses(&drive_impulses);
  AddDriveEfforts(drive_impulses, remaining, world);
  ProjectJointPositions(world);
  stats.contacts = static_cast<int>(contacts_out->size());
  for (const Contact& c : *contacts_out) stats.max_penetration = std::max(stats.max_penetration, c.depth);
  return stats;
}

}  // namespace contactsim
