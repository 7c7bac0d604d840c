#include "service/contact/soft/soft_joints.h"

#include "service/contact/joints/joint_solver.h"

namespace contactsim {

void SoftJoints::MarkJointed(const World& world, std::vector<char>* substepped) {
  for (const Joint& j : world.joints()) {
    for (const BodyId id : {j.body_a, j.body_b}) {
      if (id == kWorldBody) continue;
      const int index = world.IndexOf(id);
      if (index >= 0) (*substepped)[index] = 1;
    }
  }
}

void SoftJoints::Load(const std::vector<SoftBody>& bodies) {
  for (size_t i = 0; i < bodies.size(); ++i) {
    solver_[i].v = bodies[i].v;
    solver_[i].w = bodies[i].w;
  }
}

void SoftJoints::Begin(const World& world, double h, const std::vector<SoftBody>& bodies) {
  if (dynamics_) block_.AddDriveImpulses(&drive_impulses_);  // the previous sub-step's
  dynamics_ = HasJointDynamics(world);
  if (!dynamics_) return;
  LoadSolverBodies(world, &solver_);
  Load(bodies);
  block_.Build(world, solver_, h);
}

void SoftJoints::SolveVelocities(const World& world, double h, std::vector<SoftBody>& bodies, bool relax) {
  if (world.joints().empty()) return;
  LoadSolverBodies(world, &solver_);
  Load(bodies);
  const bool dynamics = dynamics_ && HasJointDynamics(world);  // Begin's rows are this step's
  if (dynamics && !relax) {
    block_.Solve(solver_);
  } else {
    JointSolveOptions options;
    options.joint_dynamics = !dynamics;
    ApplyJointImpulses(world, h, solver_, options, &drive_impulses_);
  }
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (solver_[i].dP.squaredNorm() + solver_[i].dL.squaredNorm() == 0.0) continue;
    bodies[i].v = solver_[i].v;
    bodies[i].w = solver_[i].w;
  }
}

void SoftJoints::StoreEfforts(World& world) {
  if (dynamics_) block_.AddDriveImpulses(&drive_impulses_);
  dynamics_ = false;
  AddDriveEfforts(drive_impulses_, world.dt, world);
  drive_impulses_.clear();
}

}  // namespace contactsim
