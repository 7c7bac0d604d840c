#include "service/contact/solver_body.h"

namespace contactsim {

void LoadSolverBodies(const World& world, std::vector<SolverBody>* bodies) {
  const auto& src = world.bodies();
  bodies->resize(src.size());
  for (size_t i = 0; i < src.size(); ++i) {
    const RigidBody& b = src[i];
    SolverBody& s = (*bodies)[i];
    s.v = b.LinearVelocity();
    s.w = b.AngularVelocity();
    s.inv_mass = b.inv_mass;
    s.inv_inertia = b.IsDynamic() ? b.InvInertiaWorld() : Mat3::Zero();
    s.dP.setZero();
    s.dL.setZero();
  }
}

void StoreSolverBodies(const std::vector<SolverBody>& bodies, World& world) {
  auto& dst = world.bodies();
  for (size_t i = 0; i < dst.size(); ++i) {
    if (!dst[i].IsDynamic()) continue;
    dst[i].P += bodies[i].dP;
    dst[i].L += bodies[i].dL;
  }
}

void DisplaceBodies(const std::vector<SolverBody>& bodies, World& world) {
  auto& dst = world.bodies();
  for (size_t i = 0; i < dst.size(); ++i) {
    if (!dst[i].IsDynamic()) continue;
    dst[i].x += bodies[i].v;
    dst[i].q = (QuatFromRotationVector(bodies[i].w) * dst[i].q).normalized();
  }
}

}  // namespace contactsim
