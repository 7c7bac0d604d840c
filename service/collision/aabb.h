// Axis-aligned bounding boxes in the world frame.
#pragma once

#include <array>

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

// The vertices of a hull that bounded its box last time, in the order
// -x, +x, -y, +y, -z, +z: between steps a body turns little, so the box's
// extreme vertices are at or next to them.
using AabbSupport = std::array<int, 6>;

// The same box; a hull of kDescentMinVertices vertices or more finds each
// extreme vertex by descent over its vertex graph (DescendVertexGraph) from
// the vertex in *support, which is updated: a few dozen vertices visited
// where the scan visits all, for the same box.
Aabb ComputeAabb(const RigidBody& body, double margin, double dt, AabbSupport* support);

}  // namespace contactsim
