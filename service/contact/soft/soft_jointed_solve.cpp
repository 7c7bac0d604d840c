#include "service/contact/soft/soft_jointed_solve.h"

#include "service/contact/joints/joint_solver.h"
#include "service/contact/jointed_contacts.h"
#include "service/contact/soft/soft_ratio_solve.h"

namespace contactsim {
namespace {

struct JointEnds {
  int a = -1, b = -1;
};

// m/s, the most a sticking friction row's compliance lets its point slip
// (friction spread by load, soft_jointed_solve.h): 1e-7 and 1e-6 hold five
// 10 kg boxes on a swing alike (0.104 mm in 3 s), but 1e-7 took 1.9-2.7
// passes a solve stage against 1.06
constexpr double kFrictionSlip = 1e-6;

}  // namespace

void SoftJointedSolve::Prepare(const World& world, const SubspaceOptions& options,
                               const std::vector<SoftBody>& bodies, const std::vector<SoftPoint>& points) {
  selected_.clear();
  if (world.joints().empty() || points.empty()) return;
  std::vector<JointEnds> joints;
  for (const Joint& j : world.joints()) {
    joints.push_back({world.IndexOf(j.body_a), j.body_b == kWorldBody ? -1 : world.IndexOf(j.body_b)});
  }
  const std::vector<int> component = JointedComponents(joints, bodies);
  if (!MarkJointedContacts(points, component, &marked_)) return;
  for (int k = 0; k < static_cast<int>(points.size()); ++k) {
    if (marked_[points[k].a] || marked_[points[k].b]) selected_.push_back(k);
  }
  load_.clear();
  for (int k : selected_) load_.push_back(points[k].lambda_n);
  options_ = options;
  options_.mass_ratio = 0.0;  // the marked components only
  options_.always = &marked_;
  options_.release_friction = true;
}

void SoftJointedSolve::Solve(const World& world, double h, const SoftPass& pass, std::vector<SoftPoint>& points,
                             std::vector<SoftBody>& bodies) {
  if (selected_.empty()) return;
  solver_.resize(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    SolverBody& s = solver_[i];
    s = SolverBody{};
    s.v = bodies[i].v, s.w = bodies[i].w;
    s.inv_mass = bodies[i].inv_mass, s.inv_inertia = bodies[i].inv_inertia;
  }
  rows_.resize(3 * selected_.size());
  for (size_t i = 0; i < selected_.size(); ++i) {
    const SoftPoint& p = points[selected_[i]];
    SoftPointRows(pass, p, bodies, p.a, p.b, static_cast<int>(3 * i), &rows_[3 * i]);
    const double bound = p.friction * load_[i];
    if (bound > 0.0) rows_[3 * i + 1].cfm = rows_[3 * i + 2].cfm = kFrictionSlip / bound;
  }
  // the joints' rows at the sub-step's poses, fresh: their impulses so far
  // are in the bodies' velocities, as ApplyJointImpulses solves them
  joint_rows_.clear();
  joint_blocks_.clear();
  BuildJointVelocityRows(world, solver_, h, JointSolverKind::kTree, &joint_rows_, &joint_blocks_,
                         JointRowMode::kVelocityGeometry);
  for (ConstraintRow& r : joint_rows_) r.lambda = 0.0;
  rows_.insert(rows_.end(), joint_rows_.begin(), joint_rows_.end());
  subspace_.Solve(rows_, solver_, options_);
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (solver_[i].dP.squaredNorm() + solver_[i].dL.squaredNorm() == 0.0) continue;
    bodies[i].v = solver_[i].v;
    bodies[i].w = solver_[i].w;
  }
  for (size_t i = 0; i < selected_.size(); ++i) {
    ReadSoftPointRows(&rows_[3 * i], points[selected_[i]]);
    load_[i] = rows_[3 * i].lambda;
  }
}

}  // namespace contactsim
