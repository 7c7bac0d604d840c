// Joints: equality constraints between two bodies, or a body and the world
// (Witkin and Baraff, SIGGRAPH 1997 course notes, "Constrained Dynamics";
// Baraff 1996, "Linear-time dynamics using Lagrange multipliers").
//
// Anchors and axes are stored in each body's frame (origin at its centre of
// mass), so they move with the bodies; for the world they are world
// coordinates. With p_A = x_A + R_A anchor_a and p_B likewise:
//   distance  C = 1/2 (d.d - length^2), d = p_A - p_B       (1 equation)
//             the classic pendulum form; A is attached at its centre of
//             mass (anchor_a = 0), the anchor is the point on B
//   ball      C = p_A - p_B                                  (3)
//   hinge     ball, and the axis fixed in A stays parallel to the axis
//             fixed in B (2 more); optional limits on the hinge angle (1)
//   fixed     ball, and the orientation of B relative to A stays the one
//             it had at creation (3 more): a weld
//   prismatic the anchor of B stays on the line through the anchor of A
//             along the axis fixed in A (2), and the orientation of B
//             relative to A stays the one it had at creation (3): a slider
// The hinge angle is the rotation of B relative to A about the axis,
// right-handed, measured from the relative orientation at creation (so a new
// hinge is at angle 0); limits bound it in [lower, upper] within [-pi, pi].
// The prismatic slide is s = a . (p_B - p_A) with a the axis fixed in A
// (m, 0 at creation, where the anchors coincide); limits bound it in any
// finite [lower, upper].
//
// Joint coordinate (hinge angle, prismatic slide): its limits are
// unilateral constraints (inactive inside the range, a one-sided row at a
// bound, as a contact); `damping` is a viscous torque or force -c qdot on
// it, and `friction` a Coulomb torque or force of at most that size
// opposing its motion (docs/physics.md, "Prismatic joints, limits, damping
// and friction").
// A mimic (URDF's <mimic>): a hinge or slider whose coordinate is held at
// q = multiplier * q_master + offset, q_master that of another joint of the
// same kind, by one equality row between the two coordinates,
//   C = q - m q_master - o,  J = J_q - m J_q_master,
// a gear between up to four bodies (Box2D's b2GearJoint couples two joint
// coordinates the same way). The contact methods that solve it are those
// whose contract says joint_couplings (docs/physics.md, "Mimic joints").
// The rows, their solvers and the drift correction live in
// service/contact/joints/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "service/physics/joint_actuator.h"
#include "service/physics/rigid_body.h"
#include "service/physics/status.h"

namespace contactsim {

using JointId = int64_t;

// body_b of a joint to the world (body ids start at 1)
constexpr BodyId kWorldBody = 0;

enum class JointKind { kDistance, kBall, kHinge, kFixed, kPrismatic };

// "distance", "ball", "hinge", "fixed", "prismatic"
const char* JointKindName(JointKind kind);
// Parses a name as printed by JointKindName; false when unknown.
bool ParseJointKind(const std::string& name, JointKind* kind);

// A joint's mimic: the master joint it follows, 0 for none.
struct JointMimic {
  JointId master = 0;
  double multiplier = 1.0;  // dimensionless
  double offset = 0.0;      // rad (hinge) or m (prismatic)
};

struct Joint {
  JointId id = 0;
  JointKind kind = JointKind::kBall;
  BodyId body_a = 0;
  BodyId body_b = kWorldBody;
  Vec3 anchor_a = Vec3::Zero();  // m, A's frame
  Vec3 anchor_b = Vec3::Zero();  // m, B's frame (world frame for the world)
  Vec3 axis_a = Vec3::UnitZ();   // unit, A's frame (hinge, prismatic)
  Vec3 axis_b = Vec3::UnitZ();   // unit, B's frame (hinge, prismatic)
  Quat rest = Quat::Identity();  // q_A^-1 q_B at creation (hinge angle 0, weld and slider pose)
  double length = 0.0;           // m (distance)
  bool limited = false;          // limits on the joint coordinate (hinge, prismatic)
  double lower = 0.0, upper = 0.0;  // rad (hinge) or m (prismatic)
  double damping = 0.0;          // N m s/rad (hinge) or N s/m (prismatic), >= 0
  double friction = 0.0;         // N m (hinge) or N (prismatic), >= 0
  bool collide_connected = false;  // may A and B touch each other (collision_filter.h)
  JointActuator actuator;        // hinge and prismatic (joint_actuator.h); none by default
  double effort = 0.0;           // N m or N: the actuator's effort u in the last step (output)
  JointMimic mimic;              // hinge and prismatic; none by default
};

// True for the kinds with one joint coordinate (hinge, prismatic): the kinds
// that take limits, damping and friction.
bool HasJointCoordinate(JointKind kind);

// A joint as it arrives from a command or a scene file: everything in world
// coordinates at the moment of creation.
struct JointSettings {
  JointKind kind = JointKind::kBall;
  BodyId body_a = 0;
  BodyId body_b = kWorldBody;
  Vec3 anchor = Vec3::Zero();     // m, world: the joint point (distance: the point on B)
  std::optional<Vec3> axis;       // world, hinge and prismatic; normalised here
  std::optional<double> length;   // m, distance only; default: the current distance
  // (lower, upper), hinge (rad) and prismatic (m) only
  std::optional<std::pair<double, double>> limits;
  double damping = 0.0;           // N m s/rad (hinge) or N s/m (prismatic); 0: none
  double friction = 0.0;          // N m (hinge) or N (prismatic); 0: none
  // Box2D's collideConnected: false (PyBullet's, Drake's and Box2D's
  // default) keeps the two bodies from touching each other
  bool collide_connected = false;
};

// The checks that need no world: finite anchor, a nonzero axis for hinge
// and prismatic, a positive length, lower <= upper (within [-pi, pi] for a
// hinge, finite for a slider), finite damping and friction >= 0, fields
// given only to the kinds they apply to, body_a a body and body_b another
// one (or the world). The message names the field and the value.
Status CheckJointSettings(const JointSettings& settings);

// Validates the settings (CheckJointSettings) against the two bodies
// (b == nullptr: the world) and builds the joint; on error `joint` is
// untouched. The caller has looked the ids up; a joint needs at least one
// dynamic body.
Status CreateJoint(const JointSettings& settings, const RigidBody& a, const RigidBody* b, Joint* joint);

// The checks of a mimic (World::SetJointMimic) against `joints`: the
// follower and the master exist, differ, are both hinges or both sliders,
// the multiplier and offset are finite, and following the masters from
// the master never comes back to the follower.
Status CheckJointMimic(const std::vector<Joint>& joints, JointId follower, const JointMimic& mimic);

// World position of an anchor stored in `body`'s frame (nullptr: the world).
Vec3 AnchorWorld(const Vec3& local, const RigidBody* body);
// Orientation of `body` (identity for the world).
Quat BodyOrientation(const RigidBody* body);
// Hinge angle (rad, in (-pi, pi]): rotation of B relative to A about the
// axis since creation.
double HingeAngle(const Joint& joint, const RigidBody& a, const RigidBody* b);
// Prismatic slide (m): a . (p_B - p_A), a the axis fixed in A.
double PrismaticSlide(const Joint& joint, const RigidBody& a, const RigidBody* b);

// The joint coordinate: the hinge angle (rad) or the prismatic slide (m);
// 0 for the kinds without one (HasJointCoordinate).
double JointPosition(const Joint& joint, const RigidBody& a, const RigidBody* b);
// Its rate (rad/s or m/s): a . (w_B - w_A) for a hinge; for a slider
// a . (pdot_B - pdot_A) + (w_A x a) . (p_B - p_A), the derivative of the
// slide with the axis turning with A. 0 for the other kinds.
double JointVelocity(const Joint& joint, const RigidBody& a, const RigidBody* b);

}  // namespace contactsim
