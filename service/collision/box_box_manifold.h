// Contact manifold of two boxes from their separating-axis result, without
// posing them (PosePolyhedron's 8 vertices, 6 planes and 12 edge
// directions a box): a face axis takes the reference face's four corners
// and the incident face's four, clipped on the stack; an edge axis the two
// edges' ends. Every vertex and plane is computed by the expressions
// PosePolyhedron uses, and the clipping and points by the steps
// PolyhedronManifold uses (face_clip.h), so the contacts are those of
// PolyhedronManifold on the posed boxes bit for bit.
#pragma once

#include "service/collision/contact.h"
#include "service/collision/polyhedron_sat.h"
#include "service/collision/posed_polyhedron.h"

namespace contactsim {

// Appends the contacts (depth > -margin) of the axis in `sat` between the
// boxes A and B; normals from A to B.
void BoxBoxManifold(const BoxPose& a, const BoxPose& b, const SatResult& sat, double margin, ContactSet* out);

}  // namespace contactsim
