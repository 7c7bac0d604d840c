// Tests of Drake's iiwa driver served by the server (service/server/arm_driver/),
// through the server logic and a recording transport: a command sets the
// arm's drives, a bad one is refused and changes nothing, the status comes
// at the driver's rate of simulated time with each field's reading, gravity
// compensation holds a horizontal arm, and the journal's replay (REWIND,
// recovery from the start's snapshot) repeats the commands.
#include <gtest/gtest.h>

#include <drake/lcmt_iiwa_command.hpp>
#include <drake/lcmt_iiwa_status.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/server/arm_server.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

using testing::ArmServer;
using testing::ChainHoldTorque;
using testing::kLinkPitch;
using testing::kComOffset;
using testing::ServerHarness;
using testing::Targets;

ServerOptions IiwaServerOptions(bool gravity_compensation = true, double kp = kDefaultArmKp, double kd = kDefaultArmKd) {
  return testing::ArmOptions("iiwa", gravity_compensation, kp, kd);
}

drake::lcmt_iiwa_command IiwaCommand(int64_t utime, std::vector<double> position, std::vector<double> torque) {
  drake::lcmt_iiwa_command m;
  m.utime = utime;
  m.num_joints = static_cast<int32_t>(position.size());
  m.joint_position = std::move(position);
  m.num_torques = static_cast<int32_t>(torque.size());
  m.joint_torque = std::move(torque);
  return m;
}

// Verifies that a command sets each drive's target, the configured gains and
// the feed-forward torque, the effort limit from the model file, and is
// answered OK on REPLY with its utime and the step it applied at (what
// --replay places it by); a command without positions (torque only) turns
// the gains off and keeps the last targets.
TEST(ArmDriverTest, CommandSetsTheDrives) {
  ArmServer a(IiwaServerOptions());
  const size_t replies = a.Replies().size();
  a.Post(IiwaCommand(7, Targets(0.1), Targets(2.0)));
  a.h.server.Tick();
  for (int i = 0; i < kArmJoints; ++i) {
    const JointActuator& d = a.joint(i).actuator;
    EXPECT_EQ(d.target_position, Targets(0.1)[i]);
    EXPECT_EQ(d.torque, Targets(2.0)[i]);
    EXPECT_EQ(d.kp, kDefaultArmKp);
    EXPECT_EQ(d.kd, kDefaultArmKd);
    EXPECT_EQ(d.target_velocity, 0.0);
    EXPECT_EQ(d.effort_limit, 10.0);  // the hand-made joints' <limit effort>
  }
  ASSERT_EQ(a.Replies().size(), replies + 1);
  EXPECT_EQ(a.Replies().back().code, reply_t::OK) << a.Replies().back().message;
  EXPECT_EQ(a.Replies().back().request_id, 7);
  EXPECT_GE(a.Replies().back().step, 0);
  EXPECT_LE(a.Replies().back().step, a.h.server.world().step);
  a.Post(IiwaCommand(8, {}, Targets(-1.0)));
  a.h.server.Tick();
  for (int i = 0; i < kArmJoints; ++i) {
    const JointActuator& d = a.joint(i).actuator;
    EXPECT_EQ(d.target_position, Targets(0.1)[i]);
    EXPECT_EQ(d.torque, Targets(-1.0)[i]);
    EXPECT_EQ(d.kp, 0.0);
    EXPECT_EQ(d.kd, 0.0);
  }
}

// Verifies that each bad command is answered on REPLY, named by the channel
// and its utime, with the reason, and that none changes a drive: a wrong
// count of positions or torques, a NaN, bytes that are no lcmt_iiwa_command,
// and a command while the world holds no arm.
TEST(ArmDriverTest, BadCommandsAreRefusedAndChangeNothing) {
  ArmServer a(IiwaServerOptions());
  a.Post(IiwaCommand(1, Targets(0.1), {}));
  a.h.server.Tick();
  struct Case {
    drake::lcmt_iiwa_command cmd;
    int32_t code;
    const char* says;
  };
  std::vector<double> nan = Targets(0.5);
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {IiwaCommand(11, std::vector<double>(6, 0.5), {}), reply_t::INVALID_ARGUMENT,
       "joint_position has 6 entries; the arm has 7 joints"},
      {IiwaCommand(12, Targets(0.5), {1, 2, 3}), reply_t::INVALID_ARGUMENT, "joint_torque has 3 entries"},
      {IiwaCommand(13, nan, {}), reply_t::INVALID_ARGUMENT, "joint_position[2] is nan, not a finite number"},
      {IiwaCommand(14, Targets(0.5), std::vector<double>(kArmJoints, std::numeric_limits<double>::infinity())),
       reply_t::INVALID_ARGUMENT, "joint_torque[0] is inf"},
  };
  for (const Case& k : cases) {
    a.Post(k.cmd);
    a.h.server.Tick();
    const reply_t r = a.Replies().back();
    EXPECT_EQ(r.client_id, "IIWA_COMMAND");
    EXPECT_EQ(r.request_id, k.cmd.utime);
    EXPECT_EQ(r.code, k.code);
    EXPECT_NE(r.message.find(k.says), std::string::npos) << r.message;
  }
  const uint8_t garbage[5] = {1, 2, 3, 4, 5};
  a.h.server.OnMessage("IIWA_COMMAND", garbage, 5);
  EXPECT_EQ(a.Replies().back().code, reply_t::DECODE_ERROR);
  for (int i = 0; i < kArmJoints; ++i) EXPECT_EQ(a.joint(i).actuator.target_position, Targets(0.1)[i]);

  ServerHarness empty(IiwaServerOptions());
  const auto bytes = testing::Encode(IiwaCommand(21, Targets(0.5), {}));
  empty.server.OnMessage("IIWA_COMMAND", bytes.data(), static_cast<int>(bytes.size()));
  empty.server.Tick();
  const reply_t r = empty.transport.All<reply_t>(empty.server.Channel("REPLY")).back();
  EXPECT_EQ(r.code, reply_t::NOT_FOUND);
  EXPECT_NE(r.message.find("the world holds no model named \"arm\""), std::string::npos) << r.message;
}

// Verifies that the status comes once per 5 ms of simulated time, stamped
// with the simulated time in microseconds, both when the step divides the
// period (1 ms: every 5th step) and when it does not (1/240 s: the first
// step of each period).
TEST(ArmDriverTest, StatusAtTheDriversRate) {
  for (double dt : {0.001, 1.0 / 240}) {
    ArmServer a(IiwaServerOptions());
    scene_cmd_t set = a.h.Scene(scene_cmd_t::SET_TIMESTEP);
    set.dt = dt;
    ASSERT_EQ(a.h.Send(set).code, reply_t::OK);
    const size_t before = a.Statuses<drake::lcmt_iiwa_status>().size();
    a.h.Step(48);
    const std::vector<drake::lcmt_iiwa_status> s = a.Statuses<drake::lcmt_iiwa_status>();
    std::vector<int64_t> got;
    for (size_t i = before; i < s.size(); ++i) got.push_back(s[i].utime);
    std::vector<int64_t> want;
    int64_t last_period = 0;
    for (int k = 1; k <= 48; ++k) {
      const double t = k * dt;
      const auto period = static_cast<int64_t>(std::floor(t * 200 + 1e-6));
      if (period != last_period) want.push_back(std::llround(t * 1e6));
      last_period = period;
    }
    EXPECT_EQ(got, want) << "dt " << dt;
  }
}

// Verifies every field of the status after a command: measured positions
// and rates are the joints', the commanded and interpolated positions the
// command's, the commanded torque its feed-forward, the measured torque the
// drive's effort plus the torque holding the horizontal chain against
// gravity (analytic), the external torque zero. The gains are 0, so that
// the chain stays horizontal whatever the targets.
TEST(ArmDriverTest, StatusFieldsAndHoldTorques) {
  ArmServer a(IiwaServerOptions(true, 0.0, 0.0));
  a.Post(IiwaCommand(3, Targets(0.2), std::vector<double>(kArmJoints, 0.0)));
  a.h.Step(5);
  const drake::lcmt_iiwa_status s = a.Statuses<drake::lcmt_iiwa_status>().back();
  ASSERT_EQ(s.num_joints, kArmJoints);
  EXPECT_EQ(s.utime, std::llround(a.h.server.world().time * 1e6));
  const World& w = a.h.server.world();
  for (int i = 0; i < kArmJoints; ++i) {
    const Joint& j = a.joint(i);
    const RigidBody& parent = *w.Find(j.body_a);
    const RigidBody& child = *w.Find(j.body_b);
    EXPECT_EQ(s.joint_position_measured[i], JointPosition(j, parent, &child));
    EXPECT_EQ(s.joint_velocity_estimated[i], JointVelocity(j, parent, &child));
    EXPECT_EQ(s.joint_position_commanded[i], Targets(0.2)[i]);
    EXPECT_EQ(s.joint_position_ipo[i], Targets(0.2)[i]);
    EXPECT_EQ(s.joint_torque_commanded[i], 0.0);
    EXPECT_NEAR(s.joint_torque_measured[i] - j.effort, ChainHoldTorque(i), 1e-6 * std::abs(ChainHoldTorque(0)));
    EXPECT_EQ(s.joint_torque_external[i], 0.0);
  }
}

// Verifies that a force pushing down on the chain's last link reads in the
// status as its joint torques: for joint i, a_i . (x_7 - p_i) x F at the
// poses the status reports, which for the horizontal chain is the push
// times the lever arm 0.2 (6 - i) + 0.1 m, positive (it turns every joint
// towards larger angles about +y); with nothing pushing, every one is 0.
TEST(ArmDriverTest, ExternalTorqueIsThePushTimesEachJointsLeverArm) {
  constexpr double kPush = 20.0;  // N, down
  ArmServer a(IiwaServerOptions());                    // gravity compensation, gains holding the pose
  a.h.Step(10);
  const drake::lcmt_iiwa_status idle = a.Statuses<drake::lcmt_iiwa_status>().back();
  for (double t : idle.joint_torque_external) EXPECT_EQ(t, 0.0);
  const BodyId hand = a.joint(kArmJoints - 1).body_b;
  body_cmd_t push = a.h.Body(body_cmd_t::APPLY_FORCE, hand);
  push.force[2] = -kPush;
  push.duration = 1.0;
  ASSERT_EQ(a.h.Send(push).code, reply_t::OK);
  a.h.Step(5);
  const drake::lcmt_iiwa_status s = a.Statuses<drake::lcmt_iiwa_status>().back();
  const World& w = a.h.server.world();
  const Vec3 force(0, 0, -kPush);
  for (int i = 0; i < kArmJoints; ++i) {
    const Joint& j = a.joint(i);
    const RigidBody* child = w.Find(j.body_b);
    const Vec3 lever = w.Find(hand)->x - AnchorWorld(j.anchor_b, child);
    const double exact = (BodyOrientation(child) * j.axis_b).dot(lever.cross(force));
    EXPECT_NEAR(s.joint_torque_external[i], exact, 1e-12 * kPush);
    // the drives hold the chain within a millimetre of horizontal
    const double level = kPush * (kLinkPitch * (kArmJoints - 1 - i) + kComOffset);
    EXPECT_NEAR(s.joint_torque_external[i], level, 1e-2 * level) << "joint " << i;
  }
}

// Verifies that gravity compensation keeps a horizontal chain with idle
// drives where it is, and that without it the chain falls.
TEST(ArmDriverTest, GravityCompensationHoldsTheArm) {
  for (bool compensate : {true, false}) {
    ArmServer a(IiwaServerOptions(compensate));
    a.h.Step(100);
    double fastest = 0;
    for (int i = 0; i < kArmJoints; ++i) {
      const Joint& j = a.joint(i);
      const World& w = a.h.server.world();
      fastest = std::max(fastest, std::abs(JointVelocity(j, *w.Find(j.body_a), w.Find(j.body_b))));
    }
    if (compensate) {
      EXPECT_LT(fastest, 1e-6);
    } else {
      EXPECT_GT(fastest, 0.1);
    }
  }
}

// Verifies that the arm's commands are journaled and replayed by REWIND: a
// REWIND to between two commands gives the first one's drives back and
// repeats the run's states, and the second command sent again at its step
// ends where the run ended.
TEST(ArmDriverTest, RewindRepeatsTheCommands) {
  ServerOptions o = IiwaServerOptions();
  o.snapshot_every = 0;  // REWIND replays from the start's snapshot
  ArmServer a(o);
  a.h.Step(5);
  a.Post(IiwaCommand(1, Targets(0.1), Targets(1.0)));
  const std::vector<uint64_t> first = a.h.Step(10);
  a.Post(IiwaCommand(2, Targets(-0.3), {}));
  a.h.Step(10);
  const uint64_t last = HashWorldState(a.h.server.world());
  scene_cmd_t rewind = a.h.Scene(scene_cmd_t::REWIND);
  rewind.target_step = 12;
  ASSERT_EQ(a.h.Send(rewind).code, reply_t::OK);
  EXPECT_EQ(HashWorldState(a.h.server.world()), first[12 - 6]);
  for (int i = 0; i < kArmJoints; ++i) {
    EXPECT_EQ(a.joint(i).actuator.target_position, Targets(0.1)[i]);
    EXPECT_EQ(a.joint(i).actuator.torque, Targets(1.0)[i]);
  }
  a.h.Step(3);
  a.Post(IiwaCommand(2, Targets(-0.3), {}));
  EXPECT_EQ(a.h.Step(10).back(), last);
}

// Verifies that a server restarted on the journal replays the arm's
// commands from the start's snapshot: the same state and the last drives.
TEST(ArmDriverTest, RecoveryRepeatsTheCommands) {
  testing::TempDir dir;
  ServerOptions o = IiwaServerOptions();
  o.journal_dir = dir.path();
  o.snapshot_every = 0;  // recovery from the start's snapshot and every record
  uint64_t last = 0;
  std::vector<int64_t> joints;
  {
    ArmServer a(o);
    joints = a.joints;
    a.h.Step(5);
    a.Post(IiwaCommand(1, Targets(0.1), Targets(1.0)));
    a.h.Step(10);
    a.Post(IiwaCommand(2, Targets(-0.3), {}));
    a.h.Step(10);
    last = HashWorldState(a.h.server.world());
  }
  ServerHarness recovered(o);
  EXPECT_EQ(HashWorldState(recovered.server.world()), last);
  for (int i = 0; i < kArmJoints; ++i) {
    const Joint* j = recovered.server.world().FindJoint(joints[i]);
    ASSERT_NE(j, nullptr);
    EXPECT_EQ(j->actuator.target_position, Targets(-0.3)[i]);
    EXPECT_EQ(j->actuator.torque, 0.0);
  }
}

}  // namespace
}  // namespace contactsim
