#include "service/contact/solver_body.h"

namespace contactsim {

namespace {

// bodies a thread loads at a time: a body's world inertia makes it ~0.2 us
// of work, so 64 of them pay for taking a chunk many times over, and a
// pyramid of 211 bodies still splits over the threads
constexpr int kSolverBodyGrain = 64;

void LoadRange(const World& world, int begin, int end, std::vector<SolverBody>* bodies) {
  const auto& src = world.bodies();
  for (int i = begin; i < end; ++i) {
    const RigidBody& b = src[i];
    SolverBody& s = (*bodies)[i];
    s.v = b.LinearVelocity();
    s.inv_mass = b.inv_mass;
    // a dynamic body's w = I_W^-1 L (RigidBody::AngularVelocity) from the
    // one world inertia: the same arithmetic, half the rotations
    if (b.IsDynamic()) {
      s.inv_inertia = b.InvInertiaWorld();
      s.w = s.inv_inertia * b.L;
    } else {
      s.inv_inertia.setZero();
      s.w = b.AngularVelocity();
    }
    s.dP.setZero();
    s.dL.setZero();
  }
}

void StoreRange(const std::vector<SolverBody>& bodies, int begin, int end, World& world) {
  auto& dst = world.bodies();
  for (int i = begin; i < end; ++i) {
    if (!dst[i].IsDynamic()) continue;
    dst[i].P += bodies[i].dP;
    dst[i].L += bodies[i].dL;
  }
}

void DisplaceRange(const std::vector<SolverBody>& bodies, int begin, int end, World& world) {
  auto& dst = world.bodies();
  for (int i = begin; i < end; ++i) {
    if (!dst[i].IsDynamic()) continue;
    dst[i].x += bodies[i].v;
    dst[i].q = (QuatFromRotationVector(bodies[i].w) * dst[i].q).normalized();
  }
}

}  // namespace

void LoadSolverBodies(const World& world, std::vector<SolverBody>* bodies) {
  bodies->resize(world.bodies().size());
  LoadRange(world, 0, static_cast<int>(bodies->size()), bodies);
}

void LoadSolverBodies(const World& world, ParallelRunner& runner, std::vector<SolverBody>* bodies) {
  bodies->resize(world.bodies().size());
  runner.For(static_cast<int>(bodies->size()), kSolverBodyGrain,
             [&](int begin, int end, int) { LoadRange(world, begin, end, bodies); });
}

void StoreSolverBodies(const std::vector<SolverBody>& bodies, World& world) {
  StoreRange(bodies, 0, static_cast<int>(world.bodies().size()), world);
}

void StoreSolverBodies(const std::vector<SolverBody>& bodies, ParallelRunner& runner, World& world) {
  runner.For(static_cast<int>(world.bodies().size()), kSolverBodyGrain,
             [&](int begin, int end, int) { StoreRange(bodies, begin, end, world); });
}

void DisplaceBodies(const std::vector<SolverBody>& bodies, World& world) {
  DisplaceRange(bodies, 0, static_cast<int>(world.bodies().size()), world);
}

void DisplaceBodies(const std::vector<SolverBody>& bodies, ParallelRunner& runner, World& world) {
  runner.For(static_cast<int>(world.bodies().size()), kSolverBodyGrain,
             [&](int begin, int end, int) { DisplaceRange(bodies, begin, end, world); });
}

}  // namespace contactsim
