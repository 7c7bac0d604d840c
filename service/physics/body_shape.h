// The shape of a new body's settings, as children posed in the settings'
// frame, and the body's shape once its centre of mass is known: a plain
// shape when it sits at the centre of mass unturned, otherwise a compound
// of children posed about the centre of mass (body_settings.h).
#pragma once

#include <vector>

#include "service/physics/body_settings.h"
#include "service/physics/hull_memo.h"

namespace contactsim {

// The solid shapes of `s` (one for a sphere, box, capsule or convex, each
// part for a compound), each posed in the settings' frame; a hull's child
// sits at its centroid. Not for planes. The message names the field
// ("parts[2].radius", "radius") and the value. Hulls come from `memo` when
// given (hull_memo.h).
Status MakeFrameChildren(const BodySettings& s, std::vector<ShapeChild>* children, HullMemo* memo = nullptr);

// The body's shape for a centre of mass `com` in the settings' frame: the
// lone child's own shape when it sits at com unturned and `s` is not a
// compound, else the compound of the children moved by -com.
Shape PlaceChildren(const BodySettings& s, const std::vector<ShapeChild>& children, const Vec3& com);

}  // namespace contactsim
