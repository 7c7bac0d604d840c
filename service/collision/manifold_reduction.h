// Reduces a contact manifold to at most four points: the deepest point, the
// point farthest from it, the point that spans the largest triangle with
// those two, and the point that adds the most area to that triangle
// (Gregorius, "Robust Contact Creation for Physics Simulations", GDC 2015),
// chosen among the points that no deeper point hides (one within 45
// degrees below it: a thin plate's top corner above a bottom one).
// Four points that span the largest area are what a solver needs to hold a
// face on a face; more add cost and no support.
#pragma once

#include <cstddef>

#include "service/collision/contact.h"

namespace contactsim {

constexpr size_t kMaxManifoldPoints = 4;

// Reduces contacts [first, end) of `contacts` in place, keeping their
// original relative order. All of them share one normal.
void ReduceManifold(size_t first, ContactSet* contacts);

}  // namespace contactsim
