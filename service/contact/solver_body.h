// Velocities of the bodies as a contact solver sees them: v and w with the
// inverse mass and world inverse inertia frozen for the solve. Impulses
// update v and w at once and are summed, so that storing them back adds
// exactly sum(J) to P and sum(r x J) to L.
#pragma once

#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/physics/world.h"

namespace contactsim {

struct SolverBody {
  Vec3 v = Vec3::Zero();        // m/s
  Vec3 w = Vec3::Zero();        // rad/s
  double inv_mass = 0.0;        // 1/kg, 0 for static and kinematic bodies
  Mat3 inv_inertia = Mat3::Zero();  // world frame
  Vec3 dP = Vec3::Zero();       // impulses applied in this solve
  Vec3 dL = Vec3::Zero();

  // J at offset r from the centre of mass
  void ApplyImpulse(const Vec3& J, const Vec3& r) {
    if (inv_mass == 0.0) return;
    v += inv_mass * J;
    const Vec3 h = r.cross(J);
    w += inv_inertia * h;
    dP += J;
    dL += h;
  }
  Vec3 PointVelocity(const Vec3& r) const { return v + w.cross(r); }
};

void LoadSolverBodies(const World& world, std::vector<SolverBody>* bodies);
// The same with the bodies split over the runner's threads.
void LoadSolverBodies(const World& world, ParallelRunner& runner, std::vector<SolverBody>* bodies);
// Adds the summed impulses to each dynamic body's P and L.
void StoreSolverBodies(const std::vector<SolverBody>& bodies, World& world);
// The same with the bodies split over the runner's threads.
void StoreSolverBodies(const std::vector<SolverBody>& bodies, ParallelRunner& runner, World& world);
// Moves each dynamic body by its solver v (m) and rotates it by w (rad,
// world): the displacement solves of split impulses and joint projection.
void DisplaceBodies(const std::vector<SolverBody>& bodies, World& world);
// The same with the bodies split over the runner's threads.
void DisplaceBodies(const std::vector<SolverBody>& bodies, ParallelRunner& runner, World& world);

}  // namespace contactsim
