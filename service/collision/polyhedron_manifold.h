// Contact manifold of two polyhedra from their separating-axis result.
//
// Face axis: the reference face is the face that defines the axis, the
// incident face is the face of the other body most anti-parallel to it. The
// incident polygon is clipped against the side planes of the reference face
// (Sutherland-Hodgman), the points closer to the reference plane than the
// margin are kept, the incident body's deepest vertex is added when clipping
// lost it (so the deepest contact has the axis's depth), and the manifold is
// reduced to four points. Each point gets
// a feature id from the two faces and the clip planes or vertex that made it.
// Edge axis: one point, midway between the closest points of the two
// supporting edges.
// (Ericson, "Real-Time Collision Detection", 8.3.4; Gregorius, "Robust Contact
// Creation for Physics Simulations", GDC 2015.)
#pragma once

#include <cstdint>
#include <vector>

#include "service/collision/contact.h"
#include "service/collision/clip_buffers.h"
#include "service/collision/polyhedron_sat.h"

namespace contactsim {

// Appends the contacts (depth > -margin) of the axis in `sat`; normals from A to B.
void PolyhedronManifold(const PosedPolyhedron& a, const PosedPolyhedron& b, const SatResult& sat,
                        double margin, ContactSet* out, ClipBuffers* buffers);

// The edge case of PolyhedronManifold, which the box-box manifold
// (box_box_manifold.h) shares with it (the face case shares face_clip.h):
// the one contact of an edge axis, midway between the closest points of
// A's edge [a0, a1] and B's edge [b0, b1].
void AppendEdgeContact(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1, const SatResult& sat,
                       double margin, ContactSet* out);

}  // namespace contactsim
