// Tests of Drake's Franka Panda driver served by the server
// (service/server/arm_driver/), through the server logic and a recording
// transport: each control mode sets the drives it maps onto, a bad command
// (wrong count, NaN, a mode that is none) is refused and changes nothing,
// the status comes at 1 kHz of simulated time with each field's reading,
// the modes move the arm as asked, and a recovery replays the commands.
#include <gtest/gtest.h>

#include <drake/lcmt_panda_command.hpp>
#include <drake/lcmt_panda_status.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/server/arm_server.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

using testing::ArmServer;
using testing::Targets;
using Status_ = drake::lcmt_panda_status;

ServerOptions PandaServerOptions(bool gravity_compensation = true, double kp = kDefaultArmKp, double kd = kDefaultArmKd) {
  return testing::ArmOptions("panda", gravity_compensation, kp, kd);
}

drake::lcmt_panda_command PandaCommand(int64_t utime, int mode, std::vector<double> position, std::vector<double> velocity,
                                  std::vector<double> torque) {
  drake::lcmt_panda_command m;
  m.utime = utime;
  m.num_joint_position = static_cast<int32_t>(position.size());
  m.joint_position = std::move(position);
  m.num_joint_velocity = static_cast<int32_t>(velocity.size());
  m.joint_velocity = std::move(velocity);
  m.num_joint_torque = static_cast<int32_t>(torque.size());
  m.joint_torque = std::move(torque);
  m.control_mode_expected = static_cast<int8_t>(mode);
  return m;
}

// A command in `mode` with each of its arrays filled (positions 0.1 + ..,
// velocities 0.2 + .., torques 1 + ..) and the others empty.
drake::lcmt_panda_command CommandInMode(int64_t utime, int mode) {
  const auto array = [&](int bit, double base) { return (mode & bit) ? Targets(base) : std::vector<double>{}; };
  return PandaCommand(utime, mode, array(kPandaPositionMode, 0.1), array(kPandaVelocityMode, 0.2),
                 array(kPandaTorqueMode, 1.0));
}

// Verifies that every set of Drake's control-mode bits sets the drives it
// maps onto: position targets with kp and kd, velocity targets (with kd,
// and kp only with positions), feed-forward torques; an unset bit leaves
// its input off (no gains, zero velocity target, zero torque), the last
// position target stays, and the status's control_mode reads the mode back.
TEST(PandaDriverTest, EachControlModeSetsItsDrives) {
  for (int mode = 1; mode <= 7; ++mode) {
    ArmServer a(PandaServerOptions());
    const size_t replies = a.Replies().size();
    std::vector<double> held;  // the start's hold targets
    for (int i = 0; i < kArmJoints; ++i) held.push_back(a.joint(i).actuator.target_position);
    a.Post(CommandInMode(mode, mode));
    a.h.server.Tick();
    ASSERT_EQ(a.Replies().size(), replies + 1) << "an accepted command is answered OK";
    EXPECT_EQ(a.Replies().back().code, reply_t::OK) << a.Replies().back().message;
    a.h.Step(1);
    const bool position = mode & kPandaPositionMode, velocity = mode & kPandaVelocityMode;
    for (int i = 0; i < kArmJoints; ++i) {
      const JointActuator& d = a.joint(i).actuator;
      EXPECT_EQ(d.target_position, position ? Targets(0.1)[i] : held[i]) << mode;
      EXPECT_EQ(d.target_velocity, velocity ? Targets(0.2)[i] : 0.0) << mode;
      EXPECT_EQ(d.torque, (mode & kPandaTorqueMode) ? Targets(1.0)[i] : 0.0) << mode;
      EXPECT_EQ(d.kp, position ? kDefaultArmKp : 0.0) << mode;
      EXPECT_EQ(d.kd, position || velocity ? kDefaultArmKd : 0.0) << mode;
    }
    const Status_ s = a.Statuses<Status_>().back();
    EXPECT_EQ(s.control_mode, mode);
    EXPECT_EQ(s.robot_mode, +Status_::kMove);
  }
}

// Verifies that each bad command is answered on REPLY, named by the channel
// and its utime, with the reason, and that none changes a drive: a wrong
// count, a NaN, modes that are none (0, an unknown bit, a negative byte),
// and arrays that disagree with the mode's bits either way.
TEST(PandaDriverTest, BadCommandsAreRefusedAndChangeNothing) {
  ArmServer a(PandaServerOptions());
  a.Post(CommandInMode(1, kPandaPositionMode | kPandaTorqueMode));
  a.h.server.Tick();
  std::vector<double> nan = Targets(0.5);
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    drake::lcmt_panda_command cmd;
    const char* says;
  };
  const std::vector<Case> cases = {
      {PandaCommand(11, kPandaPositionMode, std::vector<double>(6, 0.5), {}, {}),
       "joint_position has 6 entries; the arm has 7 joints"},
      {PandaCommand(12, kPandaVelocityMode, {}, std::vector<double>(8, 0.5), {}), "joint_velocity has 8 entries"},
      {PandaCommand(13, kPandaPositionMode, nan, {}, {}), "joint_position[2] is nan, not a finite number"},
      {PandaCommand(14, 0, {}, {}, {}), "control_mode_expected 0 is not a control mode"},
      {PandaCommand(15, 8, {}, {}, {}), "control_mode_expected 8 is not a control mode"},
      {PandaCommand(16, kPandaPositionMode | 16, Targets(0.5), {}, {}), "control_mode_expected 17 is not a control mode"},
      {PandaCommand(17, -1, Targets(0.5), Targets(0.5), Targets(0.5)), "control_mode_expected -1 is not a control mode"},
      {PandaCommand(18, kPandaPositionMode, Targets(0.5), {}, Targets(0.5)),
       "control_mode_expected 1 excludes joint_torque (mode bit 4), but it has 7 entries"},
      {PandaCommand(19, kPandaPositionMode | kPandaTorqueMode, Targets(0.5), {}, {}),
       "control_mode_expected 5 asks for joint_torque (mode bit 4), but it has 0 entries"},
  };
  for (const Case& k : cases) {
    a.Post(k.cmd);
    a.h.server.Tick();
    const reply_t r = a.Replies().back();
    EXPECT_EQ(r.client_id, "PANDA_COMMAND");
    EXPECT_EQ(r.request_id, k.cmd.utime);
    EXPECT_EQ(r.code, reply_t::INVALID_ARGUMENT);
    EXPECT_NE(r.message.find(k.says), std::string::npos) << r.message;
  }
  const uint8_t garbage[5] = {1, 2, 3, 4, 5};
  a.h.server.OnMessage("PANDA_COMMAND", garbage, 5);
  EXPECT_EQ(a.Replies().back().code, reply_t::DECODE_ERROR);
  for (int i = 0; i < kArmJoints; ++i) {
    const JointActuator& d = a.joint(i).actuator;
    EXPECT_EQ(d.target_position, Targets(0.1)[i]);
    EXPECT_EQ(d.target_velocity, 0.0);
    EXPECT_EQ(d.torque, Targets(1.0)[i]);
    EXPECT_EQ(d.kp, kDefaultArmKp);
  }
}

// Verifies that the status comes once per 1 ms of simulated time, stamped
// with the simulated time in microseconds: every step at 1 ms and at 1/240 s
// (each step enters a new period), every second step at 0.5 ms.
TEST(PandaDriverTest, StatusAtTheDriversRate) {
  for (double dt : {0.001, 1.0 / 240, 0.0005}) {
    ArmServer a(PandaServerOptions());
    scene_cmd_t set = a.h.Scene(scene_cmd_t::SET_TIMESTEP);
    set.dt = dt;
    ASSERT_EQ(a.h.Send(set).code, reply_t::OK);
    const size_t before = a.Statuses<Status_>().size();
    a.h.Step(24);
    const std::vector<Status_> s = a.Statuses<Status_>();
    std::vector<int64_t> got;
    for (size_t i = before; i < s.size(); ++i) got.push_back(s[i].utime);
    std::vector<int64_t> want;
    int64_t last_period = 0;
    for (int k = 1; k <= 24; ++k) {
      const double t = k * dt;
      const auto period = static_cast<int64_t>(std::floor(t * 1000 + 1e-6));
      if (period != last_period) want.push_back(std::llround(t * 1e6));
      last_period = period;
    }
    EXPECT_EQ(got, want) << "dt " << dt;
    for (const Status_& m : s) EXPECT_EQ(m.robot_utime, m.utime);
  }
}

// Verifies every field of the status after a velocity-and-torque command:
// measured positions and rates are the joints', the desired ones the
// drives' targets, no desired acceleration, the desired torque the
// command's, the measured torque the drive's effort plus the torque holding
// the horizontal chain against gravity (analytic), no external torque.
TEST(PandaDriverTest, StatusFieldsAndHoldTorques) {
  ArmServer a(PandaServerOptions());
  const std::vector<double> torque(kArmJoints, 0.25);
  a.Post(PandaCommand(3, kPandaVelocityMode | kPandaTorqueMode, {}, Targets(0.02), torque));
  a.h.Step(2);
  const Status_ s = a.Statuses<Status_>().back();
  ASSERT_EQ(s.num_joints, kArmJoints);
  const World& w = a.h.server.world();
  EXPECT_EQ(s.utime, std::llround(w.time * 1e6));
  EXPECT_EQ(s.control_mode, kPandaVelocityMode | kPandaTorqueMode);
  EXPECT_EQ(s.control_command_success_rate, 1.0);
  for (int i = 0; i < kArmJoints; ++i) {
    const Joint& j = a.joint(i);
    const RigidBody& parent = *w.Find(j.body_a);
    const RigidBody& child = *w.Find(j.body_b);
    EXPECT_EQ(s.joint_position[i], JointPosition(j, parent, &child));
    EXPECT_EQ(s.joint_velocity[i], JointVelocity(j, parent, &child));
    EXPECT_EQ(s.joint_position_desired[i], j.actuator.target_position);
    EXPECT_EQ(s.joint_velocity_desired[i], Targets(0.02)[i]);
    EXPECT_EQ(s.joint_acceleration_desired[i], 0.0);
    EXPECT_EQ(s.joint_torque_desired[i], torque[i]);
    const double hold = testing::ChainHoldTorque(i);
    EXPECT_NEAR(s.joint_torque[i] - j.effort, hold, 1e-3 * std::abs(testing::ChainHoldTorque(0)));
    EXPECT_EQ(s.joint_torque_external[i], 0.0);
  }
}

// Verifies that the modes move the arm as asked, gravity compensated, with
// gains that stay within the hand-made joints' 10 N m effort limit
// (kp 1000 N m/rad on errors below 6 mrad, kd 100 N m s/rad on rates
// below 0.05 rad/s): velocity targets turn every joint at its rate to
// 1 mrad/s after 0.2 s; position targets are then reached and held to
// 1 mrad, at rest to 1 mrad/s, within 1 s.
TEST(PandaDriverTest, PositionAndVelocityModesMoveTheArm) {
  constexpr double kp = 1000, kd = 100;
  ArmServer a(PandaServerOptions(true, kp, kd));
  scene_cmd_t set = a.h.Scene(scene_cmd_t::SET_TIMESTEP);
  set.dt = 0.001;  // the Panda's control cycle
  ASSERT_EQ(a.h.Send(set).code, reply_t::OK);
  std::vector<double> rate;
  for (int i = 0; i < kArmJoints; ++i) rate.push_back(0.005 * (i % 2 == 0 ? 1 : -1));
  a.Post(PandaCommand(1, kPandaVelocityMode, {}, rate, {}));
  a.h.Step(200);
  const Status_ moving = a.Statuses<Status_>().back();
  for (int i = 0; i < kArmJoints; ++i) EXPECT_NEAR(moving.joint_velocity[i], rate[i], 1e-3) << "joint " << i;
  std::vector<double> pose;
  for (int i = 0; i < kArmJoints; ++i) pose.push_back(moving.joint_position[i] - 0.001 * i);
  a.Post(PandaCommand(2, kPandaPositionMode, pose, {}, {}));
  a.h.Step(1000);
  const Status_ held = a.Statuses<Status_>().back();
  for (int i = 0; i < kArmJoints; ++i) {
    EXPECT_NEAR(held.joint_position[i], pose[i], 1e-3) << "joint " << i;
    EXPECT_NEAR(held.joint_velocity[i], 0.0, 1e-3) << "joint " << i;
  }
}

// Verifies that a server restarted on the journal replays the Panda's
// commands, decoded by the Panda's protocol: the same state and drives.
TEST(PandaDriverTest, RecoveryRepeatsTheCommands) {
  testing::TempDir dir;
  ServerOptions o = PandaServerOptions();
  o.journal_dir = dir.path();
  o.snapshot_every = 0;  // recovery from the start's snapshot and every record
  uint64_t last = 0;
  std::vector<int64_t> joints;
  {
    ArmServer a(o);
    joints = a.joints;
    a.h.Step(5);
    a.Post(CommandInMode(1, kPandaPositionMode | kPandaTorqueMode));
    a.h.Step(10);
    a.Post(CommandInMode(2, kPandaVelocityMode));
    a.h.Step(10);
    last = HashWorldState(a.h.server.world());
  }
  testing::ServerHarness recovered(o);
  EXPECT_EQ(HashWorldState(recovered.server.world()), last);
  for (int i = 0; i < kArmJoints; ++i) {
    const Joint* j = recovered.server.world().FindJoint(joints[i]);
    ASSERT_NE(j, nullptr);
    EXPECT_EQ(j->actuator.target_velocity, Targets(0.2)[i]);
    EXPECT_EQ(j->actuator.kp, 0.0);
    EXPECT_EQ(j->actuator.torque, 0.0);
  }
}

}  // namespace
}  // namespace contactsim
