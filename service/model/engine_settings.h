// The builder's plans (body_plan.h) as the engine's body and joint
// settings: a body is a compound of its links' collision elements with the
// file's mass properties (body_settings.h), a moving joint a hinge or a
// slider with its limits, damping and friction (and an actuator with the
// file's effort and velocity limits), and self-collision off a
// negative collision group (collision_filter.h). What the engine cannot
// take (a planar joint, a body without a shape) is refused here with an
// error that names the model, the link or joint.
#pragma once

#include <string>

#include "service/model/body_plan.h"
#include "service/model/model_description.h"
#include "service/physics/body_settings.h"
#include "service/physics/hull_memo.h"
#include "service/physics/joint.h"
#include "service/physics/status.h"

namespace contactsim::model {

// A body's settings from its plan, with its owner link's frame at `owner_W`
// in the world. A static body (the fixed base) gets no mass. A mesh becomes
// the hull of at most `max_hull_vertices` of its vertices (0: the full hull;
// hull_vertex_budget.h), taken from `memo` when another link's mesh had
// the same vertices.
Status MakeBodySettings(const BodyPlan& plan, const Pose& owner_W, bool is_static, int max_hull_vertices,
                        const std::string& where, HullMemo* memo, BodySettings* settings);

// A moving joint's settings with the child link's frame at `child_W` in the
// world at q = 0; the body ids are left for the caller. Fixed joints are
// merged and floating joints add nothing, so neither comes here.
Status MakeJointSettings(const ModelJoint& joint, const Pose& child_W, const std::string& where,
                         JointSettings* settings);

// The actuator a moving joint gets: the file's effort and velocity limits
// (URDF <limit effort velocity>, SDF <limit><effort><velocity>; 0 or none
// given: no limit) and no torque or gains, so that it moves nothing until a
// command drives it (World::SetJointActuator keeps the limits then only if
// the command repeats them).
JointActuator MakeJointActuator(const ModelJoint& joint);

// Self-collision off: every body of the model in one group that never
// collides with itself (`group` < 0, as Box2D's negative groups).
Status ApplySelfCollision(bool self_collide, int group, BodySettings* settings);

}  // namespace contactsim::model
