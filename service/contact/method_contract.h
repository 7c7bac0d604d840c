// What a contact method promises to simulate (docs/physics.md, "Method
// contract"): joints, restitution, kinematic bodies, its friction model and
// compound bodies.
// Each method's contract is declared once, in its row of the registry
// (contact_method_registry.h); the server refuses a world the active method
// cannot honour (method_support.h) and publishes the contract in STATUS.
#pragma once

#include <string>

namespace contactsim {

struct MethodContract {
  // equality constraints (service/physics/joint.h) with their limits,
  // damping, friction and actuators (joint_actuator.h): every method that
  // takes joints applies their actuators, so they need no entry of their own
  bool joints = false;
  bool restitution = false;       // material restitution e > 0 makes bounces
  bool kinematic_bodies = false;  // bodies moved by their set velocity push the others
  // The friction law, in words: "coulomb disk" (|lambda_t| <= mu lambda_n),
  // "coulomb pyramid" (each tangent alone), "regularized" (a spring or a
  // smoothing of the stick-slip switch), with what decides between them.
  const char* friction = "";
  // compound bodies (shape.h): a body of several shapes collides child by
  // child
  bool compound_bodies = true;
  // Each contact's normal and friction force (or impulse) is reported, so
  // that a contact sensor can sum the wrench a body received (contact_wrench.h).
  bool contact_forces = false;
  // triangle meshes and heightfields (docs/physics.md, "Triangle meshes and
  // heightfields"): their contacts come from the narrowphase, triangle by
  // triangle with the edge rule
  bool triangle_surfaces = true;
  // mimic joints (physics/joint.h, JointMimic): the coupling row between
  // two joint coordinates is solved with the joints (joint_couplings.h)
  bool joint_couplings = false;
};

// "joints=yes; restitution=no; kinematic=yes; contact_forces=yes; friction=...", the text
// STATUS carries (lcmtypes/status_t.lcm, method_contract); friction comes
// last because its words hold spaces.
std::string DescribeContract(const MethodContract& contract);

}  // namespace contactsim
