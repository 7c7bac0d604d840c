// A compound body's children as bodies of their own for the pair functions
// (collide_pairs.h), which read a body's pose and shape: child k's world
// pose is the body's pose times the child's, X_WC = X_WB X_BC
// (shape.h, "compound"). Only compound bodies take this path; the others
// are collided as they are, with no indirection.
#pragma once

#include "service/physics/rigid_body.h"

namespace contactsim {

// Child `child` of `parent` posed in the world, with the parent's id and
// motion type, so that pair functions order and cache it as the parent.
RigidBody ChildBody(const RigidBody& parent, const ShapeChild& child);

// The number of pieces a body collides as: its children for a compound, 1
// otherwise; and piece k (the body itself when it is not a compound).
int PieceCount(const RigidBody& body);
RigidBody PieceBody(const RigidBody& body, int k);

}  // namespace contactsim
