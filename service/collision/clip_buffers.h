// The polygons of face clipping (face_clip.h), kept by a caller between
// calls (collide_pairs.h's PolyhedronScratch) so that a step allocates
// nothing once their capacity is reached.
#pragma once

#include <cstdint>
#include <vector>

#include "service/physics/math.h"

namespace contactsim {

// A point of the clipped incident polygon: its position and the incident
// vertex index, or the hash of the clip that made it.
struct ClipPoint {
  Vec3 p;
  uint32_t tag;
};

struct ClipBuffers {
  std::vector<ClipPoint> poly, clipped;
};

}  // namespace contactsim
