// The contact points of a clipped incident polygon (see face_clip.h).
#include "service/collision/face_clip.h"

#include <limits>

#include "service/collision/collide_pairs.h"

namespace contactsim {

double AppendFacePoints(const ReferenceFace& ref, int inc_face, const ClipPoint* poly, size_t count, double margin,
                        ContactSet* out) {
  const uint32_t ref_side = ref.ref_is_a ? 0u : 1u;
  // every point's id starts with the same four parts
  const uint32_t faces_id =
      FeatureId({kTagFace, ref_side, static_cast<uint32_t>(ref.index), static_cast<uint32_t>(inc_face)});
  double deepest = -std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < count; ++k) {
    const ClipPoint& cp = poly[k];
    const double s = ref.normal.dot(cp.p) - ref.offset;  // < 0 below the reference face
    if (-s <= -margin) continue;
    // cp.p is on the incident surface; the reference surface is -s n_ref away
    const Vec3 surface_a = ref.ref_is_a ? Vec3(cp.p - s * ref.normal) : cp.p;
    AppendContact(surface_a, ref.normal_ab, -s, FeatureIdAppend(faces_id, cp.tag), out);
    deepest = std::max(deepest, -s);
  }
  return deepest;
}

}  // namespace contactsim
