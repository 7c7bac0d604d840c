// Detection for methods that look ahead over a whole step from one
// narrowphase (xpbd's sub-steps, the soft step's speculative contacts):
// contacts within `margin`, and for each pair that can close by more than
// the margin within dt (motion_bound.h) within its own reach, so that a
// fast body is seen before it arrives and cannot pass through a thin one
// between two detections.
#pragma once

#include "service/collision/collision_detector.h"
#include "service/collision/contact.h"
#include "service/physics/world.h"

namespace contactsim {

void DetectAhead(const World& world, CollisionDetector& detector, double margin, double dt, ContactSet* contacts);

}  // namespace contactsim
