// Narrowphase: contact points of one pair of bodies, looked up in a table by
// the two shape types (as MuJoCo's mjCOLLISIONFUNC).
#pragma once

#include "service/collision/contact.h"
#include "service/physics/rigid_body.h"

namespace contactsim {

// Appends the contacts of bodies a and b (indices ia, ib in the world) with
// depth > -margin to `out`; normals point from a to b. Returns the number of
// contacts appended.
int Collide(const RigidBody& a, int ia, const RigidBody& b, int ib, double margin, ContactSet* out);

}  // namespace contactsim
