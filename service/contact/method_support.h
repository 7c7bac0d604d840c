// Whether a contact method can honour a world, read from its contract
// (method_contract.h, declared in the registry's table), so that a world
// a method cannot step is refused with a status instead of being stepped
// wrongly: the barrier method (IPC on affine bodies, barrier/) has no joint
// constraints, no restitution (its implicit step is inelastic) and moves
// kinematic bodies outside its solve, and stepping such a world with it
// would drop them silently (docs/physics.md, "Method contract"). The
// server asks before it adds a joint or a body, sets a material, switches
// the method, loads a scene or starts.
#pragma once

#include <string>

#include "service/physics/rigid_body.h"
#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

// Ok when the method can step `world`; else FailedPrecondition naming the
// method, what it cannot simulate and where the world holds it
// ("... does not simulate joints ...", "... does not simulate restitution ...").
Status CheckMethodSupports(const std::string& method, const World& world);

// Ok when the method can take a joint; else FailedPrecondition.
Status CheckMethodAcceptsJoint(const std::string& method);

// Ok when the method can take a mimic joint (joint_couplings); else
// FailedPrecondition.
Status CheckMethodAcceptsMimic(const std::string& method);

// Ok when the method reports contact forces for a contact sensor to sum;
// else FailedPrecondition.
Status CheckMethodAcceptsContactSensor(const std::string& method);

// Ok when the method can simulate `body` (its restitution, its motion
// type, a compound shape): an added body, or one whose material changes; else
// FailedPrecondition naming `what` ("body 3", "the new sphere").
Status CheckMethodAcceptsBody(const std::string& method, const RigidBody& body, const std::string& what);

}  // namespace contactsim
