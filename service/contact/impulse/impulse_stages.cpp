// The impulse method's passes over the contacts colour by colour as the
// stages of one ParallelRunner::Stages call each (impulse_method.h,
// "Threads"), built with the stage list lcp, soft and xpbd use
// (colour_stages.h): the collision phase's passes, the contact phase's warm
// start and sweeps, the split impulse's sweeps. Each pass is followed by a
// serial stage that takes the pass's result and, once the phase is done,
// turns the remaining passes' stages into no-ops. One thread runs the same
// stages in the same order, so the result does not depend on the thread
// count.
#include <algorithm>
#include <cmath>

#include "service/contact/colour_stages.h"
#include "service/contact/impulse/impulse_method.h"
#include "service/contact/overflow_runs.h"

namespace contactsim {

namespace {

using Fn = ParallelRunner::StageFn;

// Fewer groups than this keep the caller's order, as the overflow (its
// independent runs one stage a pass, overflow_runs.h): a colour of a few
// dozen pairs is a few microseconds of work, about what the threads'
// meeting at a stage costs. It also keeps small worlds on the
// serial sweep in contact order, under which a 20-cube aligned stack
// stands (2e-9 m sideways in 10 s): coloured alternately, the stack's pairs
// let a rocking mode grow from round-off, 12 mm in 10 s at a
// velocity_tolerance of 1e-5 m/s (docs/physics.md, "impulse on threads").
constexpr int kMinColouredGroups = 256;

double Largest(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

}  // namespace

void ImpulseMethod::RunPasses(int passes, const bool& done, const std::function<void(ColourStages&)>& prologue,
                              const std::function<void(ColourStages&)>& add_pass) {
  int run = 0, batch = 1;
  do {
    ColourStages list(&stages_, runner_->threads());
    if (run == 0 && prologue) prologue(list);
    for (int p = 0; p < batch && run < passes; ++p, ++run) add_pass(list);
    runner_->Stages(stages_);
    batch *= 2;
  } while (run < passes && !done);
}

void ImpulseMethod::SetColourRoles(const World& world) {
  roles_.resize(solver_.size());
  for (size_t i = 0; i < solver_.size(); ++i) {
    roles_[i] = solver_[i].inv_mass > 0.0 ? ColourRole::kColoured : ColourRole::kFixed;
  }
  // the contacts on a jointed body keep their order: the joints are solved
  // between the sweeps as a block of their own (joint_block.h)
  for (const Joint& j : world.joints()) {
    for (const BodyId id : {j.body_a, j.body_b}) {
      const int i = id == kWorldBody ? -1 : world.IndexOf(id);
      if (i >= 0 && roles_[i] == ColourRole::kColoured) roles_[i] = ColourRole::kSerial;
    }
  }
}

// The contacts of one body pair (a face-on-face manifold has four) collide
// at once: their impulses j_k >= 0 are found together, by Gauss-Seidel with
// accumulated clamping, so that each contact leaves at -e times its approach
// speed or faster. Applying the points one after another instead gives the
// first corner the whole impulse: a box hit face-on by a wall would leave
// spinning (measured: 0.33 rad/s and 3% too fast). Different pairs still
// take turns, pass after pass, which is what carries the impulse down a
// Newton's cradle (Guendelman et al. 2003).
BlockColours ImpulseMethod::ColourGroups(const std::vector<ContactRow>& rows, std::vector<NormalBlock>* groups) const {
  BlockColours colours;
  if (static_cast<int>(groups->size()) >= kMinColouredGroups) {
    colours = ColourBlocks(rows, roles_, groups);
  } else {
    colours.starts = {0};  // every group in the overflow
  }
  // the overflow's groups that share no moving body with the others on
  // the threads, each run in its order: the same sweep bit for bit
  SplitOverflow(rows, roles_, &colours, groups);
  return colours;
}

int ImpulseMethod::CollisionPhase(std::vector<ContactRow>& rows) {
  const int n = static_cast<int>(rows.size());
  if (n == 0) return 0;
  groups_.clear();
  for (int k = 0; k < n;) {
    int end = k + 1;
    while (end < n && rows[end].a == rows[k].a && rows[end].b == rows[k].b) ++end;
    groups_.push_back(NormalBlock{k, end - k, false, Eigen::Matrix4d::Zero()});
    k = end;
  }
  colours_ = ColourGroups(rows, &groups_);
  const int groups = static_cast<int>(groups_.size());
  target_.resize(n);
  impulse_.resize(n);
  group_hit_.assign(groups, 0);
  // A pair whose last check found nothing approaching, and neither of whose
  // bodies an impulse has changed since, would find the same: it is skipped
  // with the same answer. Each check has its own order number in the
  // phase, pass * groups + g (the groups run in that order: a colour's
  // pairs share no moving body, so none of them can change another's
  // bodies); a body records the number of the last check that pushed it.
  checked_at_.assign(groups, -1);
  pushed_at_.assign(solver_.size(), -1);
  int passes = 0;
  bool done = false;  // no pair approached in the last pass
  const Fn pass = [&](int i, int j) {
    if (done) return;
    for (int g = i; g < j; ++g) group_hit_[g] = CollideChanged(g, int64_t{passes} * groups + g, rows);
  };
  const Fn check = [&](int, int) {
    if (done) return;
    done = std::none_of(group_hit_.begin(), group_hit_.end(), [](char hit) { return hit != 0; });
    if (!done) ++passes;
  };
  RunPasses(params_.collision_passes, done, nullptr, [&](ColourStages& list) {
    list.AddColours(pass, colours_, groups);
    list.AddSerial(check);
  });
  return passes;
}

bool ImpulseMethod::CollideChanged(int g, int64_t order, std::vector<ContactRow>& rows) {
  const NormalBlock& group = groups_[g];
  const int a = rows[group.first].a, b = rows[group.first].b;
  // a check's own push counts: its points may still approach after it
  if (checked_at_[g] >= 0 && std::max(pushed_at_[a], pushed_at_[b]) < checked_at_[g]) return false;
  checked_at_[g] = order;
  if (!CollideGroup(group, rows)) return false;
  // fixed bodies take no impulse (and are shared across a colour's pairs)
  if (solver_[a].inv_mass != 0.0) pushed_at_[a] = order;
  if (solver_[b].inv_mass != 0.0) pushed_at_[b] = order;
  return true;
}

bool ImpulseMethod::CollideGroup(const NormalBlock& g, std::vector<ContactRow>& rows) {
  const int begin = g.first, end = g.first + g.count;
  bool hit = false;
  for (int k = begin; k < end; ++k) hit = hit || NormalVelocity(rows[k], responses_[k]) < -params_.collision_threshold;
  if (!hit) return false;
  // Newton's law per point: v_n+ >= -e v_n-; points that barely approach
  // or separate only must not approach. Holding a separating point to
  // its separating speed instead pushes it whenever another point's
  // impulse slows it: a box resting on the ground, struck by a sphere,
  // was thrown up at 14 m/s as the two pairs took turns (+513 J).
  for (int k = begin; k < end; ++k) {
    const double vn = NormalVelocity(rows[k], responses_[k]);
    target_[k] = vn < -params_.collision_threshold ? -rows[k].restitution * vn : 0.0;
    impulse_[k] = 0.0;
  }
  for (int it = 0; it < params_.iterations; ++it) {
    double worst = 0.0;
    for (int k = begin; k < end; ++k) {
      ContactRow& row = rows[k];
      const double next = std::max(0.0, impulse_[k] + (target_[k] - NormalVelocity(row, responses_[k])) * row.mass_n);
      const double d = next - impulse_[k];
      impulse_[k] = next;
      PushNormal(row, responses_[k], d);
      worst = std::max(worst, std::abs(d) * row.k_n);
    }
    if (worst < params_.velocity_tolerance) break;
  }
  // Coulomb friction of the collision: stop the sliding if mu j allows it
  for (int k = begin; k < end; ++k) {
    ContactRow& row = rows[k];
    const double j = impulse_[k];
    row.lambda_n += j;
    if (j <= 0.0 || row.friction <= 0.0) continue;
    Vec3 vt = row.FrictionVelocity(solver_);
    vt -= row.n * row.n.dot(vt);
    const double speed_t = vt.norm();
    if (speed_t <= 1e-12) continue;
    const Vec3 t = vt / speed_t;
    const double jt = std::min(speed_t / FrictionInverseMass(row, t, solver_), row.friction * j);
    row.ApplyFriction(-jt * t, solver_);
    row.lambda_t1 -= jt * t.dot(row.t1);
    row.lambda_t2 -= jt * t.dot(row.t2);
  }
  return true;
}

int ImpulseMethod::SweepContacts(const World& world, double h, int max_sweeps, std::vector<ContactRow>& rows,
                                 bool* converged, bool* interleave) {
  colours_ = ColourGroups(rows, &blocks_);
  const int blocks = static_cast<int>(blocks_.size());
  block_worst_.assign(blocks, 0.0);
  int sweeps = 0;
  bool done = false;  // set by the serial stage after a sweep, read by the later stages
  *converged = *interleave = false;
  const Fn warm_start = [&](int i, int j) {
    for (int b = i; b < j; ++b) {
      for (int k = blocks_[b].first; k < blocks_[b].first + blocks_[b].count; ++k) {
        const ContactRow& row = rows[k];
        if (row.lambda_n == 0.0 && row.lambda_t1 == 0.0 && row.lambda_t2 == 0.0) continue;
        if (row.fa == row.ra && row.fb == row.rb) {  // one impulse where friction acts at the contact point
          row.Apply(row.lambda_n * row.n + row.lambda_t1 * row.t1 + row.lambda_t2 * row.t2, solver_);
        } else {
          row.Apply(row.lambda_n * row.n, solver_);
          row.ApplyFriction(row.lambda_t1 * row.t1 + row.lambda_t2 * row.t2, solver_);
        }
      }
    }
  };
  // the joint rows' velocity products at the warm-started velocities, the
  // nearest to the step's end that is known before the sweeps; joints and
  // contacts as two blocks of one Gauss-Seidel iteration (joint_block.h):
  // the joints solved exactly after every sweep only where a contact acts
  // on a jointed body, and none on two of one articulated body
  // (JointVelocityBlock::SelfContact)
  const Fn build_joints = [&](int, int) {
    joints_.Build(world, solver_, h);
    bool touched = false, self = false;
    for (const ContactRow& row : rows) {
      touched = touched || joints_.Jointed(row.a) || joints_.Jointed(row.b);
      self = self || joints_.SelfContact(row.a, row.b);
    }
    *interleave = touched && !self;
  };
  const Fn sweep = [&](int i, int j) {
    if (done) return;
    for (int b = i; b < j; ++b) block_worst_[b] = SweepBlock(blocks_[b], rows);
  };
  const Fn check = [&](int, int) {
    if (done) return;
    const double worst = std::max(Largest(block_worst_), *interleave ? joints_.Solve(solver_) : 0.0);
    ++sweeps;
    done = *converged = worst < params_.velocity_tolerance;
  };
  const auto warm = [&](ColourStages& list) {
    list.AddColours(warm_start, colours_, blocks);
    list.AddSerial(build_joints);
  };
  RunPasses(max_sweeps, done, warm, [&](ColourStages& list) {
    list.AddColours(sweep, colours_, blocks);
    list.AddSerial(check);
  });
  return sweeps;
}

void ImpulseMethod::SweepPositions(const std::vector<double>& target) {
  GroupNormalBlocks(split_rows_, &ContactRow::n, &blocks_);
  colours_ = ColourGroups(split_rows_, &blocks_);
  const int blocks = static_cast<int>(blocks_.size());
  block_worst_.assign(blocks, 0.0);
  bool done = false;
  const Fn sweep = [&](int i, int j) {
    if (done) return;
    for (int b = i; b < j; ++b) {
      double worst = 0.0;
      for (int k = blocks_[b].first; k < blocks_[b].first + blocks_[b].count; ++k) {
        ContactRow& row = split_rows_[k];
        const double gap = target[k] - row.NormalVelocity(solver_);
        const double next = std::max(0.0, row.lambda_n + gap * row.mass_n);
        const double d = next - row.lambda_n;
        row.lambda_n = next;
        row.Apply(d * row.n, solver_);
        worst = std::max(worst, std::abs(d) * row.k_n);
      }
      block_worst_[b] = worst;
    }
  };
  // m/s of pseudo-velocity: far below any correction a step makes
  const Fn check = [&](int, int) { done = done || Largest(block_worst_) < 1e-9; };
  RunPasses(params_.iterations, done, nullptr, [&](ColourStages& list) {
    list.AddColours(sweep, colours_, blocks);
    list.AddSerial(check);
  });
}

}  // namespace contactsim
