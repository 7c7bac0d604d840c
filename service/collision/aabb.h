// Axis-aligned bounding boxes in the world frame.
#pragma once

#include "service/physics/math.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

struct Aabb {
  Vec3 min = Vec3::Zero();  // m
  Vec3 max = Vec3::Zero();  // m

  bool Overlaps(const Aabb& o) const {
    return (min.array() <= o.max.array()).all() && (o.min.array() <= max.array()).all();
  }
  void Inflate(double margin) {
    min.array() -= margin;
    max.array() += margin;
  }
};

// Box of the body at its current pose, grown by `margin` on every side and
// swept by the displacement v dt of the step (so fast bodies are not missed).
// Planes get a very large box on their solid side.
Aabb ComputeAabb(const RigidBody& body, double margin, double dt);

}  // namespace contactsim
