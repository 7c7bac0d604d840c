// The edge-edge mollifier of Incremental Potential Contact (Li et al. 2020,
// sec. 4.2, eq. 13): the distance of two nearly parallel edges is
// ill-conditioned (the closest points slide along the edges, and a tilt of
// theta moves the computed distance by about theta times the edge length),
// which made the barrier energy jump by ~1e-12 J between a configuration and
// its neighbours and stalled the line search on boxes resting on boxes. IPC
// multiplies the edge-edge barrier by
//   m(c) = (c / eps_x) (2 - c / eps_x) for c < eps_x, 1 beyond,
//   c = |e_a x e_b|^2,  eps_x = 1e-3 |E_a|^2 |E_b|^2  (rest edge lengths),
// which vanishes for parallel edges; their contact is carried by the
// point-triangle pairs of the same faces.
#pragma once

#include "service/contact/barrier/affine_body.h"
#include "service/contact/barrier/contact_primitives.h"

namespace contactsim {

struct EdgeMollifier {
  double m = 1.0;                       // the factor
  Vec12 grad_a = Vec12::Zero();         // dm/dq_a
  Vec12 grad_b = Vec12::Zero();         // dm/dq_b
};

// The mollifier of an edge-edge pair of bodies a and b with the linear parts
// Aa, Ab of their affine maps, and of an edge against a triangle surface
// with the surface edge `dist` chose (surface_primitives.h); m = 1 with zero
// gradients for other kinds.
EdgeMollifier MollifyEdgeEdge(const BodyGeometry& a, const Mat3& Aa, const BodyGeometry& b, const Mat3& Ab,
                              const PrimitivePair& pair, const PairDistance& dist);

// m of rest edges Ua, Ub that are now u, v.
double EdgeMollifierValue(const Vec3& Ua, const Vec3& Ub, const Vec3& u, const Vec3& v);

}  // namespace contactsim
