// One triangle of a static surface (a triangle mesh or a heightfield) in
// the form the narrowphase and the ray cast take it; the edge rule that
// fills `active_edges` is in triangle_surface.h.
#pragma once

#include <array>
#include <cstdint>

#include "service/physics/math.h"

namespace contactsim {

struct SurfaceTriangle {
  std::array<Vec3, 3> v;        // m, counter-clockwise seen from the front
  Vec3 normal = Vec3::UnitZ();  // unit, out of the front
  uint8_t active_edges = 7;     // bit k: edge v[k] -> v[k+1] is active
  // bit k: edge k is convex by more than kConvexEdgeAngle, or open: an edge
  // a body's edge or face can touch before its vertices touch the faces
  // (the barrier's surface distances, contact/barrier/surface_primitives.h)
  uint8_t convex_edges = 7;
  uint32_t index = 0;           // mesh triangle, or 2 cell + half of a heightfield
};

}  // namespace contactsim
