// Tests of the joints on the wire (service/server/joint_state_message.h)
// through the server logic and a recording transport: STATE's joint block
// equals the JOINT_STATE of the same step under every method that takes
// joints, a jointless STATE grows by its count alone, and the joint_state
// option decides when JOINT_STATE goes out beside STATE.
#include <gtest/gtest.h>

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/joint_state_t.hpp>

#include <cstring>

#include "service/proto/model.pb.h"
#include "service/scene/model_proto.h"
#include "service/server/actuator_update.h"
#include "tests/model/hand_made_models.h"
#include "tests/server/server_harness.h"

namespace contactsim {
namespace {

using testing::ServerHarness;

ServerOptions JointStateServerOptions(JointStatePolicy policy = JointStatePolicy::kAlways) {
  ServerOptions o;
  o.prefix = "J";
  o.joint_state = policy;
  return o;
}

// The hand-made three-link arm (two hinges) with a fixed base, driven by
// position actuators so that its efforts are not zero, and a loose hinge
// after it: joints of a model, then one of none.
void AddArmAndHinge(ServerHarness& h) {
  model_cmd_t m{};
  m.client_id = "test";
  m.op = model_cmd_t::LOAD;
  m.format = model_cmd_t::FORMAT_RESOLVED;
  m.fixed_base = true;
  proto::ModelDescription p;
  SaveModelDescription(model::testing::Arm(), &p);
  const std::string bytes = p.SerializeAsString();
  m.resolved.assign(bytes.begin(), bytes.end());
  m.position[2] = 1.0;
  m.orientation[0] = 1.0;
  reply_t r = h.Send(m);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;

  body_cmd_t box = h.Box(0.1, Vec3(2, 0, 1.5));
  box.mass = 1.0;
  r = h.Send(box);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  joint_cmd_t j{};
  j.client_id = "test";
  j.op = joint_cmd_t::ADD;
  j.kind = joint_cmd_t::HINGE;
  j.body_a = r.ids[0];
  j.anchor[0] = 2.0;
  j.anchor[2] = 2.0;
  j.has_axis = true;
  j.axis[1] = 1.0;
  r = h.Send(j);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;

  ActuatorUpdate u;
  u.fields = kActuatorKp | kActuatorKd | kActuatorTargetPosition;
  JointActuator drive;
  drive.kp = 50.0;
  drive.kd = 2.0;
  drive.target_position = 0.3;
  u.values.assign(2, drive);
  u.model = 1;
  actuator_cmd_t a{};
  a.client_id = "test";
  a.op = actuator_cmd_t::SET;
  a.joints = EncodeActuatorUpdate(u);
  r = h.Send(a);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
}

// Bit for bit: the same doubles, not merely close ones.
bool SameDoubleBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

// Verifies, under every method that takes joints, that each STATE's joint
// block lists the joints of the JOINT_STATE of its step (published just
// before it) in the same order with the same bits: the model's two hinges
// by model, then the loose hinge with model 0; the driven joints' efforts
// are not zero.
TEST(JointStateMessageTest, StateCarriesTheJointStateOfItsStepUnderEveryMethod) {
  for (const ContactMethodEntry& e : ContactMethodTable()) {
    if (!e.contract.joints) continue;
    SCOPED_TRACE(e.name);
    ServerHarness h(JointStateServerOptions(), e.name);
    AddArmAndHinge(h);
    h.Step(5);
    const std::vector<state_t> states = h.transport.All<state_t>("J_STATE");
    const std::vector<joint_state_t> joints = h.transport.All<joint_state_t>("J_JOINT_STATE");
    ASSERT_FALSE(states.empty());
    const state_t& s = states.back();
    ASSERT_EQ(s.step, 5);
    const joint_state_t* js = nullptr;
    for (const joint_state_t& j : joints) js = j.step == s.step ? &j : js;
    ASSERT_NE(js, nullptr);
    EXPECT_EQ(s.num_joints, 3);
    EXPECT_EQ(s.num_joints, js->num_joints);
    EXPECT_EQ(s.joint_ids, js->joint_ids);
    EXPECT_EQ(s.joint_model_ids, js->model_ids);
    EXPECT_EQ(s.joint_model_ids, (std::vector<int64_t>{1, 1, 0}));
    EXPECT_TRUE(SameDoubleBits(s.joint_positions, js->positions));
    EXPECT_TRUE(SameDoubleBits(s.joint_velocities, js->velocities));
    EXPECT_TRUE(SameDoubleBits(s.joint_efforts, js->efforts));
    EXPECT_NE(s.joint_efforts[0], 0.0);
    EXPECT_EQ(js->names, (std::vector<std::string>{"shoulder", "elbow", std::to_string(js->joint_ids[2])}));
  }
}

// Verifies that a world without joints sends an empty joint block: STATE
// is four bytes (the count) longer than its bodies and header.
TEST(JointStateMessageTest, AJointlessStateGrowsByItsCountAlone) {
  ServerHarness h(JointStateServerOptions());
  ASSERT_EQ(h.Send(h.Box(0.1, Vec3(0, 0, 1))).code, reply_t::OK);
  h.Step(1);
  const state_t s = h.transport.All<state_t>("J_STATE").back();
  EXPECT_EQ(s.num_joints, 0);
  state_t without = s;
  const int header = 8 + 8 + 8 + 8 + 8 + 8 + 8 + 4;  // fingerprint, six fields, num_bodies
  const int body = 8 + 13 * 8;
  EXPECT_EQ(without.getEncodedSize(), header + body + 4);
  EXPECT_TRUE(h.transport.All<joint_state_t>("J_JOINT_STATE").empty());
}

// Registers a lockstep controller "ctl", runs `steps` steps answering each
// STATE with an empty input, and returns how many JOINT_STATEs went out
// meanwhile.
size_t JointStatesInLockstep(ServerHarness& h, int steps) {
  scene_cmd_t reg = h.Scene(scene_cmd_t::REGISTER_CONTROLLER);
  reg.client_id = "ctl";
  EXPECT_EQ(h.Send(reg).code, reply_t::OK);
  scene_cmd_t mode = h.Scene(scene_cmd_t::SET_MODE);
  mode.mode = scene_cmd_t::LOCKSTEP;
  EXPECT_EQ(h.Send(mode).code, reply_t::OK);
  EXPECT_EQ(h.Send(h.Scene(scene_cmd_t::RESUME)).code, reply_t::OK);
  const size_t before = h.transport.All<joint_state_t>("J_JOINT_STATE").size();
  const int64_t start = h.server.world().step;
  for (int64_t k = start + 1; k <= start + steps; ++k) {
    input_t in{};
    in.client_id = "ctl";
    in.step = k;
    in.joints = EncodeActuatorUpdate(ActuatorUpdate());
    h.Post(in);
    EXPECT_TRUE(h.server.Tick()) << k;
  }
  EXPECT_EQ(h.server.world().step, start + steps);
  EXPECT_EQ(h.transport.All<state_t>("J_STATE").back().num_joints, 3);
  return h.transport.All<joint_state_t>("J_JOINT_STATE").size() - before;
}

// Verifies the joint_state option: always publishes JOINT_STATE with every
// lockstep STATE; outside_lockstep publishes it with a STEP's STATE but not
// while a controller is registered in lockstep; off never does, yet an
// ACTUATOR_CMD STATE still gets one. STATE carries the joints in all three.
TEST(JointStateMessageTest, TheOptionDecidesWhenJointStateGoesOut) {
  {
    ServerHarness h(JointStateServerOptions(JointStatePolicy::kAlways));
    AddArmAndHinge(h);
    EXPECT_EQ(JointStatesInLockstep(h, 4), 4u);
  }
  {
    ServerHarness h(JointStateServerOptions(JointStatePolicy::kOutsideLockstep));
    AddArmAndHinge(h);
    h.Step(2);
    EXPECT_FALSE(h.transport.All<joint_state_t>("J_JOINT_STATE").empty());
    EXPECT_EQ(JointStatesInLockstep(h, 4), 0u);
  }
  {
    ServerHarness h(JointStateServerOptions(JointStatePolicy::kOff));
    AddArmAndHinge(h);
    h.Step(2);
    EXPECT_TRUE(h.transport.All<joint_state_t>("J_JOINT_STATE").empty());
    EXPECT_EQ(JointStatesInLockstep(h, 2), 0u);
    actuator_cmd_t ask{};
    ask.client_id = "test";
    ask.op = actuator_cmd_t::STATE;
    ask.joints = EncodeActuatorUpdate(ActuatorUpdate());
    ASSERT_EQ(h.Send(ask).code, reply_t::OK);
    EXPECT_EQ(h.transport.All<joint_state_t>("J_JOINT_STATE").size(), 1u);
  }
}

}  // namespace
}  // namespace contactsim
