// Reduces a contact manifold to at most four points: the deepest point, the
// point farthest from it, the point that spans the largest triangle with
// those two, and the point that adds the most area to that triangle
// (Gregorius, "Robust Contact Creation for Physics Simulations", GDC 2015),
// chosen among the points that no deeper point hides (one within 45
// degrees below it: a thin plate's top corner above a bottom one). When
// the four are not all level (kFlushSlope) and some of the points span a
// face flush with the contact plane at the deepest point, the four are
// chosen among that face's points instead (a hull's landing face, not its
// neighbours' vertices above it within the margin; docs/physics.md,
// "Manifold reduction keeps a flush face").
// Four points that span the largest area are what a solver needs to hold a
// face on a face; more add cost and no support.
#pragma once

#include <cstddef>

#include "service/collision/contact.h"

namespace contactsim {

constexpr size_t kMaxManifoldPoints = 4;

// Two points are level when their depths differ by at most this fraction
// of their in-plane distance (about 1.1 degrees): a face lands with its
// corners level, its neighbour faces' vertices rise from it at their
// dihedral angles (tens of degrees on a random hull).
constexpr double kFlushSlope = 0.02;
// A level set spans a face when its widest triangle is at least this
// fraction of its long side wide; narrower, it is an edge to a solver.
constexpr double kMinFaceWidth = 0.1;

// Reduces contacts [first, end) of `contacts` in place, keeping their
// original relative order. All of them share one normal.
void ReduceManifold(size_t first, ContactSet* contacts);

}  // namespace contactsim
