// A contact point between two bodies.
//
// Conventions (also in docs/conventions.md):
// - normal is a unit vector in the world frame pointing from body A to body
//   B: pushing B along +normal and A along -normal separates them;
// - depth > 0 is penetration (m); depth < 0 is a gap, reported only for
//   speculative contacts within the detector's margin;
// - point is in the world frame, midway between the two surfaces.
#pragma once

#include <cstdint>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

struct Contact {
  int a = -1;                 // index of body A in World::bodies() (this step)
  int b = -1;                 // index of body B
  BodyId id_a = 0;
  BodyId id_b = 0;
  Vec3 point = Vec3::Zero();  // m, world
  Vec3 normal = Vec3::UnitZ();// unit, world, from A to B
  double depth = 0.0;         // m, > 0 overlapping
  uint32_t feature_id = 0;    // stable across steps for the same features (warm start)

  // written by the contact method that resolved it (N s or N, see the method)
  double normal_value = 0.0;
  Vec3 tangent_value = Vec3::Zero();
};

using ContactSet = std::vector<Contact>;

}  // namespace contactsim
