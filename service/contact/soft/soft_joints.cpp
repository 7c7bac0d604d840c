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

void SoftJoints::SolveVelocities(const World& world, double h, std::vector<SoftBody>& bodies) {
  if (world.joints().empty()) return;
  LoadSolverBodies(world, &solver_);
  for (size_t i = 0; i < bodies.size(); ++i) {
    solver_[i].v = bodies[i].v;
    solver_[i].w = bodies[i].w;
  }
  ApplyJointImpulses(world, h, solver_);
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (solver_[i].dP.squaredNorm() + solver_[i].dL.squaredNorm() == 0.0) continue;
    bodies[i].v = solver_[i].v;
    bodies[i].w = solver_[i].w;
  }
}

}  // namespace contactsim
