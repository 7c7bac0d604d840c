// Separating-axis test of two boxes in closed form: the 15 candidate axes
// (3 face normals of each box, 9 cross products of their edge directions)
// with each box's support along an axis from its half extents, r = sum_k
// h_k |u . e_k| (Gottschalk, Lin and Manocha, "OBBTree", SIGGRAPH 1996;
// ODE's dBoxBox), so that nothing is posed and no vertex is visited.
//
// It returns what FindSeparatingAxis (polyhedron_sat.h) returns for the
// two posed boxes, up to round-off: the same face and edge indices of the
// unit box topology (posed_polyhedron.h), the same preferences and early
// out. Each pair of edge directions gives one edge candidate, oriented
// from A to B, whose edges are the boxes' supporting edges along it: the
// Minkowski-face pair that the Gauss-map test of the general test keeps.
// Where that test keeps none (faces exactly parallel), the candidate here
// ties a face axis, and the preference for faces makes the same choice.
#pragma once

#include "service/collision/polyhedron_sat.h"
#include "service/collision/posed_polyhedron.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

// a and b must be boxes.
SatResult FindBoxBoxSeparatingAxis(const RigidBody& a, const RigidBody& b, double early_out);
// The same on the boxes' poses, taken once for the pair's test and manifold.
SatResult FindBoxBoxSeparatingAxis(const BoxPose& a, const BoxPose& b, double early_out);

// The axis, normal and separation of FindBoxBoxSeparatingAxis, bit for bit,
// for a contact: the nine edge pairs are tested only when a closed form of
// their separations (ODE's, from the entries of Ra^T Rb) says that one may
// beat the faces' choice or the early out. Resting boxes' faces win by the
// preference tolerances, so most touching pairs skip the pairs' loop, two
// fifths of the test. max_separation and max_normal then cover the faces
// only: use FindBoxBoxSeparatingAxis where they are needed.
SatResult FindBoxBoxContactAxis(const BoxPose& a, const BoxPose& b, double early_out);

}  // namespace contactsim
