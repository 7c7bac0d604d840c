// A simulated parallel gripper's two fingers in the world: the model's two
// prismatic finger joints, each finger's opening direction, and the
// separation they make. As the arm's joints (arm_joints.h), they are looked
// up by name each time, so a world replaced by RESET, RESTORE or REWIND is
// always the one read.
//
// Each finger joint's coordinate q is 0 where the finger is closed on the
// gripper's centre, and its limits lie on one side of 0, the side it opens
// to: Drake's WSG model opens its left finger to q < 0 and its right to
// q > 0 (SchunkWsgPdController: "When the gripper is open, q0 < 0 and
// q1 > 0"), the Panda's hand opens both to q > 0. With s = +1 or -1 that
// side, the finger's opening is o = s q and the separation of the fingers
// is o_0 + o_1, Drake's WSG "position".
#pragma once

#include <string>

#include "service/physics/status.h"
#include "service/physics/world.h"

namespace contactsim {

struct WsgFingers {
  JointId joints[2] = {0, 0};
  double sign[2] = {1, 1};            // s: +1 opens to q > 0, -1 to q < 0
  double effort_limit[2] = {0, 0};    // N, from the file; infinity when none given
  double min_separation = 0;          // m, both fingers at their closed limits
  double max_separation = 0;          // m, both fingers at their open limits
};

// The fingers `joints` of the model named `model`. NotFound for a missing
// model or joint; FailedPrecondition, naming the joint, for one that is not
// prismatic, has no limits, or whose limits cross 0.
Status FindWsgFingers(const World& world, const std::string& model, const std::string (&joints)[2],
                      WsgFingers* out);

// Each finger joint's coordinate q (m) and rate (m/s): JointPosition and
// JointVelocity (physics/joint.h).
void ReadWsgFingers(const World& world, const WsgFingers& fingers, double (&q)[2], double (&v)[2]);

// The fingers' separation (m) and its rate (m/s): o_0 + o_1 and its
// derivative.
void ReadWsgSeparation(const World& world, const WsgFingers& fingers, double* separation, double* speed);

}  // namespace contactsim
