// Tests of the joint channels through the server logic and a recording
// transport: ACTUATOR_CMD's standing settings (fields not given are kept,
// a refused command changes nothing), JOINT_STATE's joints and order, a
// lockstep input's joint commands (refused ones hold the step; the standing
// settings return after the step), and snapshots, REWIND and journal
// recovery keeping the settings.
#include <gtest/gtest.h>

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/joint_state_t.hpp>

#include <cmath>
#include <limits>

#include "service/server/actuator_update.h"
#include "tests/server/server_harness.h"
#include "tests/server/temp_dir.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

ServerOptions ActuatorServerOptions() {
  ServerOptions o;
  o.prefix = "A";
  return o;
}

// One value per joint of each field given.
actuator_cmd_t Actuator(int8_t op, const std::vector<int64_t>& joints, const ActuatorUpdate& values = {}) {
  ActuatorUpdate u = values;
  u.joints = joints;
  if (u.values.empty()) u.values.resize(joints.size());
  actuator_cmd_t m{};
  m.client_id = "test";
  m.op = op;
  m.joints = EncodeActuatorUpdate(u);
  return m;
}

ActuatorUpdate Fields(uint8_t fields, const JointActuator& value, size_t n = 1) {
  ActuatorUpdate u;
  u.fields = fields;
  u.values.assign(n, value);
  return u;
}

// A 1 kg box hanging from a hinge about y at the world point (0, 0, 2), a
// slider along z, and a distance joint: joints 1, 2 and 3.
void AddJoints(ServerHarness& h) {
  for (double x : {0.0, 1.0, 2.0}) {
    body_cmd_t add = h.Box(0.1, Vec3(x, 0, 1.5));
    add.mass = 1.0;
    ASSERT_EQ(h.Send(add).code, reply_t::OK);
  }
  const auto joint = [&](int8_t kind, int64_t body, const Vec3& anchor, bool axis) {
    joint_cmd_t j{};
    j.client_id = "test";
    j.op = joint_cmd_t::ADD;
    j.kind = kind;
    j.body_a = body;
    for (int i = 0; i < 3; ++i) j.anchor[i] = anchor[i];
    j.has_axis = axis;
    j.axis[kind == joint_cmd_t::HINGE ? 1 : 2] = 1.0;
    const reply_t r = h.Send(j);
    ASSERT_EQ(r.code, reply_t::OK) << r.message;
  };
  joint(joint_cmd_t::HINGE, 1, Vec3(0, 0, 2), true);
  joint(joint_cmd_t::PRISMATIC, 2, Vec3(1, 0, 1.5), true);
  joint(joint_cmd_t::DISTANCE, 3, Vec3(2, 0, 2.5), false);
}

const JointActuator& ActuatorOf(const ServerHarness& h, JointId id) { return h.server.world().FindJoint(id)->actuator; }

// Verifies that SET changes only the fields given (new targets keep the
// gains), answers with the joint ids, and CLEAR removes the actuator.
TEST(SimServerActuatorsTest, SetKeepsTheFieldsNotGivenAndClearRemoves) {
  ServerHarness h(ActuatorServerOptions());
  AddJoints(h);
  JointActuator v;
  v.kp = 100.0;
  v.kd = 10.0;
  reply_t r = h.Send(Actuator(actuator_cmd_t::SET, {1, 2}, Fields(kActuatorKp | kActuatorKd, v, 2)));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(r.ids, (std::vector<int64_t>{1, 2}));
  v.target_position = 0.5;
  r = h.Send(Actuator(actuator_cmd_t::SET, {1}, Fields(kActuatorTargetPosition, v)));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(ActuatorOf(h, 1).kp, 100.0);
  EXPECT_EQ(ActuatorOf(h, 1).kd, 10.0);
  EXPECT_EQ(ActuatorOf(h, 1).target_position, 0.5);
  EXPECT_EQ(ActuatorOf(h, 2).target_position, 0.0);
  EXPECT_TRUE(std::isinf(ActuatorOf(h, 1).effort_limit));
  r = h.Send(Actuator(actuator_cmd_t::CLEAR, {1}));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(ActuatorOf(h, 1).kp, 0.0);
  EXPECT_EQ(ActuatorOf(h, 2).kp, 100.0);
}

// Verifies that one bad joint or value refuses the whole command with a
// message naming it, and no joint changes.
TEST(SimServerActuatorsTest, ARefusedCommandChangesNoJoint) {
  ServerHarness h(ActuatorServerOptions());
  AddJoints(h);
  JointActuator v;
  v.kp = 7.0;
  struct Case {
    actuator_cmd_t cmd;
    int32_t code;
    const char* says;
  };
  JointActuator bad = v;
  bad.kp = -1.0;
  JointActuator nan = v;
  nan.target_position = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {Actuator(actuator_cmd_t::SET, {1, 99}, Fields(kActuatorKp, v, 2)), reply_t::NOT_FOUND, "unknown joint id 99"},
      {Actuator(actuator_cmd_t::SET, {1, 3}, Fields(kActuatorKp, v, 2)), reply_t::FAILED_PRECONDITION,
       "joint 3 is a distance joint"},
      {Actuator(actuator_cmd_t::SET, {1, 2}, Fields(kActuatorKp, bad, 2)), reply_t::INVALID_ARGUMENT,
       "joints[0].kp must be finite and >= 0, got -1"},
      {Actuator(actuator_cmd_t::SET, {2}, Fields(kActuatorTargetPosition, nan)), reply_t::INVALID_ARGUMENT,
       "joints[0].target_position must be a finite number, got nan"},
      {Actuator(actuator_cmd_t::SET, {2, 2}, Fields(kActuatorKp, v, 2)), reply_t::INVALID_ARGUMENT, "named twice"},
  };
  for (const Case& c : cases) {
    const reply_t r = h.Send(c.cmd);
    EXPECT_EQ(r.code, c.code) << r.message;
    EXPECT_NE(r.message.find(c.says), std::string::npos) << r.message;
    EXPECT_EQ(ActuatorOf(h, 1).kp, 0.0);
    EXPECT_EQ(ActuatorOf(h, 2).kp, 0.0);
  }
}

// Verifies that JOINT_STATE goes out with STATE (same step, just before
// it) and lists the hinge and the slider, not the distance joint, named by
// id, with the falling slider's coordinate and rate those of its body (its
// slide a . (p_world - p_box) grows as the box falls at g t); a STATE
// request publishes it on demand.
TEST(SimServerActuatorsTest, JointStateListsTheJointsWithACoordinate) {
  ServerHarness h(ActuatorServerOptions());
  AddJoints(h);
  h.Step(3);
  const std::vector<joint_state_t> all = h.transport.All<joint_state_t>("A_JOINT_STATE");
  ASSERT_FALSE(all.empty());
  const joint_state_t& js = all.back();
  EXPECT_EQ(js.step, 3);
  EXPECT_EQ(js.step, h.transport.All<state_t>("A_STATE").back().step);
  EXPECT_EQ(js.joint_ids, (std::vector<int64_t>{1, 2}));
  EXPECT_EQ(js.model_ids, (std::vector<int64_t>{0, 0}));
  EXPECT_EQ(js.names, (std::vector<std::string>{"1", "2"}));
  const double dt = h.server.world().dt, g = -h.server.world().gravity.z();
  const RigidBody& box = *h.server.world().Find(2);
  EXPECT_NEAR(js.positions[1], 1.5 - box.x.z(), 1e-12);
  EXPECT_NEAR(js.velocities[1], g * dt * 3, 1e-12);
  const size_t before = all.size();
  const reply_t r = h.Send(Actuator(actuator_cmd_t::STATE, {}));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(h.transport.All<joint_state_t>("A_JOINT_STATE").size(), before + 1);
}

// Verifies that a lockstep input's joints are checked on arrival (a refused
// input holds the step), that a good one is journaled with explicit ids and
// that after its step every joint has its standing settings again.
TEST(SimServerActuatorsTest, LockstepJointCommandsActForOneStep) {
  ServerHarness h(ActuatorServerOptions());
  AddJoints(h);
  JointActuator standing;
  standing.kp = 5.0;
  ASSERT_EQ(h.Send(Actuator(actuator_cmd_t::SET, {1}, Fields(kActuatorKp, standing))).code, reply_t::OK);
  scene_cmd_t reg = h.Scene(scene_cmd_t::REGISTER_CONTROLLER);
  reg.client_id = "ctl";
  ASSERT_EQ(h.Send(reg).code, reply_t::OK);
  scene_cmd_t mode = h.Scene(scene_cmd_t::SET_MODE);
  mode.mode = scene_cmd_t::LOCKSTEP;
  ASSERT_EQ(h.Send(mode).code, reply_t::OK);
  ASSERT_EQ(h.Send(h.Scene(scene_cmd_t::RESUME)).code, reply_t::OK);

  JointActuator push;
  push.torque = 3.0;
  push.kp = 50.0;
  input_t in{};
  in.client_id = "ctl";
  in.step = 1;
  ActuatorUpdate u = Fields(kActuatorTorque | kActuatorKp, push, 1);
  u.joints = {3};  // the distance joint: refused
  in.joints = EncodeActuatorUpdate(u);
  h.Post(in);
  EXPECT_FALSE(h.server.Tick());
  EXPECT_EQ(h.server.world().step, 0);
  const reply_t refused = h.transport.All<reply_t>("A_REPLY").back();
  EXPECT_EQ(refused.code, reply_t::FAILED_PRECONDITION) << refused.message;
  EXPECT_NE(refused.message.find("input for step 1: joint 3 is a distance joint"), std::string::npos);

  uint64_t digest_without = 0;
  for (int k = 1; k <= 2; ++k) {
    u.joints = {1};
    in.step = k;
    in.joints = EncodeActuatorUpdate(k == 1 ? u : ActuatorUpdate());
    h.Post(in);
    ASSERT_TRUE(h.server.Tick()) << k;
    ASSERT_EQ(h.server.world().step, k);
    EXPECT_EQ(ActuatorOf(h, 1).kp, 5.0);
    EXPECT_EQ(ActuatorOf(h, 1).torque, 0.0);
    if (k == 2) digest_without = h.transport.All<state_t>("A_STATE").back().input_digest;
  }
  EXPECT_NE(h.transport.All<state_t>("A_STATE").end()[-2].input_digest, digest_without);
}

// Verifies that a snapshot slot, REWIND and recovery from the journal give
// every joint its standing settings back.
TEST(SimServerActuatorsTest, SnapshotsRewindAndRecoveryKeepTheSettings) {
  testing::TempDir dir;
  ServerOptions o = ActuatorServerOptions();
  o.journal_dir = dir.path();
  o.snapshot_every = 4;
  JointActuator v;
  v.kp = 40.0;
  v.target_position = 0.25;
  v.effort_limit = 12.0;
  {
    ServerHarness h(o);
    AddJoints(h);
    h.Step(3);
    const uint8_t fields = kActuatorKp | kActuatorTargetPosition | kActuatorEffortLimit;
    ASSERT_EQ(h.Send(Actuator(actuator_cmd_t::SET, {1, 2}, Fields(fields, v, 2))).code, reply_t::OK);
    h.Step(6);
    scene_cmd_t rewind = h.Scene(scene_cmd_t::REWIND);
    rewind.target_step = 7;
    ASSERT_EQ(h.Send(rewind).code, reply_t::OK);
    EXPECT_EQ(ActuatorOf(h, 1).kp, 40.0);
    EXPECT_EQ(ActuatorOf(h, 1).target_position, 0.25);
    rewind.target_step = 2;
    ASSERT_EQ(h.Send(rewind).code, reply_t::OK);
    EXPECT_EQ(ActuatorOf(h, 1).kp, 0.0);
    ASSERT_EQ(h.Send(Actuator(actuator_cmd_t::SET, {1, 2}, Fields(fields, v, 2))).code, reply_t::OK);
    h.Step(7);
    scene_cmd_t save = h.Scene(scene_cmd_t::SNAPSHOT);
    save.name = "a";
    ASSERT_EQ(h.Send(save).code, reply_t::OK);
    ASSERT_EQ(h.Send(Actuator(actuator_cmd_t::CLEAR, {1, 2})).code, reply_t::OK);
    scene_cmd_t restore = h.Scene(scene_cmd_t::RESTORE);
    restore.name = "a";
    ASSERT_EQ(h.Send(restore).code, reply_t::OK);
    EXPECT_EQ(ActuatorOf(h, 2).kp, 40.0);
    EXPECT_EQ(ActuatorOf(h, 2).effort_limit, 12.0);
    h.Step(2);
  }
  ServerHarness recovered(o);
  EXPECT_EQ(recovered.server.world().step, 11);
  EXPECT_EQ(ActuatorOf(recovered, 1).kp, 40.0);
  EXPECT_EQ(ActuatorOf(recovered, 2).effort_limit, 12.0);
  EXPECT_TRUE(std::isinf(ActuatorOf(recovered, 2).velocity_limit));
}

}  // namespace
}  // namespace contactsim
