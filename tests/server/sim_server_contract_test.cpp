// Tests of the contact methods' contracts through the server logic and a
// recording transport (service/contact/method_contract.h, method_support.h):
// STATUS says what the active method simulates, and a command that would
// make the method drop part of the world (a joint, a restitution or a
// kinematic body under barrier) is refused with FAILED_PRECONDITION saying why, leaving the
// world as it was.
#include <gtest/gtest.h>

#include <contactsim/protocol.hpp>
#include <contactsim/status_t.hpp>

#include "service/contact/contact_method_registry.h"
#include "service/scene/scene_spec.h"
#include "service/server/server_config.h"
#include "tests/server/sim_server_fixture.h"

namespace contactsim {
namespace {

using testing::RecordingTransport;

class SimServerContractTest : public testing::SimServerTest {
 protected:
  reply_t SetMethod(const std::string& name) {
    scene_cmd_t m = Scene(scene_cmd_t::SET_METHOD);
    m.method = name;
    return Send(m);
  }
  body_cmd_t Inelastic(body_cmd_t m) {
    m.has_restitution = true;
    m.restitution = 0.0;
    return m;
  }
  body_cmd_t Material(int64_t id, double restitution) {
    body_cmd_t m{};
    m.client_id = "test";
    m.op = body_cmd_t::SET_MATERIAL;
    m.body_id = id;
    m.has_restitution = true;
    m.restitution = restitution;
    return m;
  }
};

// Verifies that a switch to barrier is refused while a body has restitution
// > 0 (the sphere's 0.5), naming the body and the value, and the
// method stays; with every restitution set to 0 the switch is taken.
TEST_F(SimServerContractTest, SwitchToBarrierIsRefusedWhileABodyBounces) {
  const int64_t ball = Send(Sphere(0.1, Vec3(0, 0, 1))).ids[0];
  const uint64_t before = HashWorldState(server_.world());
  reply_t r = SetMethod("barrier");
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_EQ(r.message, "contact method barrier does not simulate restitution: body 1 has restitution 0.5; "
                       "give it restitution 0 or choose impulse, penalty, xpbd, lcp or soft");
  EXPECT_STREQ(server_.method().Name(), "impulse");
  EXPECT_EQ(HashWorldState(server_.world()), before);
  ASSERT_EQ(Send(Material(ball, 0.0)).code, reply_t::OK);
  r = SetMethod("barrier");
  EXPECT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_STREQ(server_.method().Name(), "barrier");
}

// Verifies that under barrier a bouncy body is refused, whether added or
// given restitution by SET_MATERIAL, and that the world is left as it was;
// an inelastic one, and a friction change, are taken.
TEST_F(SimServerContractTest, BarrierRefusesBodiesWithRestitution) {
  ASSERT_EQ(SetMethod("barrier").code, reply_t::OK);
  reply_t r = Send(Sphere(0.1, Vec3(0, 0, 1)));
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(r.message.find("does not simulate restitution: the new sphere has restitution 0.5"), std::string::npos)
      << r.message;
  EXPECT_TRUE(server_.world().bodies().empty());
  r = Send(Inelastic(Sphere(0.1, Vec3(0, 0, 1))));
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  const int64_t ball = r.ids[0];
  r = Send(Material(ball, 0.3));
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(r.message.find("body 1 has restitution 0.3"), std::string::npos) << r.message;
  EXPECT_EQ(server_.world().Find(ball)->material.restitution, 0.0);
  body_cmd_t friction = Material(ball, 0.0);
  friction.has_restitution = false;
  friction.has_friction = true;
  friction.friction = 0.9;
  EXPECT_EQ(Send(friction).code, reply_t::OK);
  EXPECT_EQ(server_.world().Find(ball)->material.friction, 0.9);
}

// Verifies that barrier refuses kinematic bodies (it moves them before its
// solve, so their motion pushes nothing): one added under it, and a switch
// to it while the world holds one.
TEST_F(SimServerContractTest, BarrierRefusesKinematicBodies) {
  body_cmd_t platform = Inelastic(Sphere(0.5, Vec3(0, 0, 0)));
  platform.kinematic = true;
  platform.linear_velocity[2] = 0.2;
  ASSERT_EQ(Send(platform).code, reply_t::OK);
  reply_t r = SetMethod("barrier");
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_EQ(r.message, "contact method barrier does not simulate kinematic bodies: body 1 is kinematic; make it "
                       "dynamic or fixed, or choose impulse, penalty, xpbd, lcp or soft");
  body_cmd_t remove{};
  remove.client_id = "test";
  remove.op = body_cmd_t::REMOVE;
  remove.body_id = 1;
  ASSERT_EQ(Send(remove).code, reply_t::OK);
  ASSERT_EQ(SetMethod("barrier").code, reply_t::OK);
  r = Send(platform);
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(r.message.find("the new sphere is kinematic"), std::string::npos) << r.message;
  EXPECT_TRUE(server_.world().bodies().empty());
}

// Verifies that barrier refuses joints both ways: a joint added under it,
// and a switch to it while the world holds one.
TEST_F(SimServerContractTest, BarrierRefusesJoints) {
  const int64_t bob = Send(Inelastic(Sphere(0.1, Vec3(0, 0, 1)))).ids[0];
  ASSERT_EQ(Send(Joint(joint_cmd_t::DISTANCE, bob, 0, Vec3(0, 0, 2))).code, reply_t::OK);
  reply_t r = SetMethod("barrier");
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_EQ(r.message, "contact method barrier does not simulate joints; the world holds 1 joint(s): remove them "
                       "or choose impulse, penalty, xpbd, lcp or soft");
  joint_cmd_t remove{};
  remove.client_id = "test";
  remove.op = joint_cmd_t::REMOVE;
  remove.joint_id = 1;
  ASSERT_EQ(Send(remove).code, reply_t::OK);
  ASSERT_EQ(SetMethod("barrier").code, reply_t::OK);
  r = Send(Joint(joint_cmd_t::DISTANCE, bob, 0, Vec3(0, 0, 2)));
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_EQ(r.message,
            "contact method barrier does not simulate joints: choose impulse, penalty, xpbd, lcp or soft before adding one");
  EXPECT_TRUE(server_.world().joints().empty());
}

// Verifies that a scene the active method cannot honour is refused whole:
// the bounce scene (restitution 0.5) under barrier leaves the world empty.
TEST_F(SimServerContractTest, BarrierRefusesABouncyScene) {
  ASSERT_EQ(SetMethod("barrier").code, reply_t::OK);
  scene_cmd_t load = Scene(scene_cmd_t::LOAD_SCENE);
  load.path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/bounce.pbtxt";
  const reply_t r = Send(load);
  EXPECT_EQ(r.code, reply_t::FAILED_PRECONDITION);
  EXPECT_NE(r.message.find("does not simulate restitution: body 1 \"ground\" has restitution 0.5"),
            std::string::npos)
      << r.message;
  EXPECT_TRUE(server_.world().bodies().empty());
}

// Verifies that a server configured with barrier and a bouncy scene does
// not start (the configuration cannot be honoured), saying why.
TEST(SimServerContractInitTest, ConfiguredMethodMustHonourTheScene) {
  SceneSpec spec;
  ASSERT_TRUE(LoadSceneFile(std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/bounce.pbtxt", &spec).ok());
  RecordingTransport transport;
  ServerOptions o;
  o.prefix = "I";
  o.start_paused = true;
  SimServer server(o, &transport);
  std::shared_ptr<ContactMethod> barrier;
  ASSERT_TRUE(MakeContactMethod("barrier", {}, &barrier).ok());
  const Status st = server.Init(&spec, barrier);
  EXPECT_EQ(st.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(st.message().find("does not simulate restitution"), std::string::npos) << st.message();
}

class SimServerContractStatusTest : public ::testing::TestWithParam<std::string> {};

// Verifies that STATUS carries the contract of the active method, as the
// registry declares it, in the documented form.
TEST_P(SimServerContractStatusTest, StatusCarriesTheActiveMethodsContract) {
  RecordingTransport transport;
  ServerOptions o;
  o.prefix = "C";
  o.start_paused = true;
  SimServer server(o, &transport);
  std::shared_ptr<ContactMethod> method;
  ASSERT_TRUE(MakeContactMethod(GetParam(), {}, &method).ok());
  ASSERT_TRUE(server.Init(nullptr, method).ok());
  const std::vector<status_t> status = transport.All<status_t>(server.Channel("STATUS"));
  ASSERT_FALSE(status.empty());
  const MethodContract& c = FindContactMethod(GetParam())->contract;
  EXPECT_EQ(status.back().method, GetParam());
  EXPECT_EQ(status.back().method_contract, DescribeContract(c));
  auto yes = [](bool b) { return b ? "yes" : "no"; };
  const std::string expected_start = std::string("joints=") + yes(c.joints) + "; restitution=" + yes(c.restitution) +
                                     "; kinematic=" + yes(c.kinematic_bodies) +
                                     "; contact_forces=" + yes(c.contact_forces) + "; friction=";
  EXPECT_EQ(status.back().method_contract.rfind(expected_start, 0), 0u) << status.back().method_contract;
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, SimServerContractStatusTest, ::testing::ValuesIn(ContactMethodNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

class SimServerDefaultWorldTest : public ::testing::TestWithParam<std::string> {
 protected:
  // Hands one command to the server, applies it and returns its reply.
  template <typename Msg>
  reply_t Send(SimServer& server, const char* channel, const Msg& m) {
    const std::vector<uint8_t> bytes = testing::Encode(m);
    server.OnMessage(server.Channel(channel), bytes.data(), static_cast<int>(bytes.size()));
    server.Tick();
    return transport_.All<reply_t>(server.Channel(protocol::kReply)).back();
  }
  // ADD of a body with nothing but its shape and place: the server's
  // default material.
  static body_cmd_t Add(int8_t shape, double z) {
    body_cmd_t m{};
    m.client_id = "default";
    m.op = body_cmd_t::ADD;
    m.shape = shape;
    m.radius = 0.1;
    m.half_extents[0] = m.half_extents[1] = m.half_extents[2] = 0.1;
    m.plane_normal[2] = 1.0;
    m.position[0] = 3.0;
    m.position[2] = z;
    m.orientation[0] = 1.0;
    return m;
  }
  RecordingTransport transport_;
};

// Verifies that a default world takes every registered method: the server
// as config/server.pbtxt sets it up (its scene and method), plus a sphere, a
// box and a plane added over BODY_CMD with the default material, switches
// to the method by SET_METHOD and steps under it.
TEST_P(SimServerDefaultWorldTest, SwitchesToTheMethod) {
  const std::string path = std::string(CONTACTSIM_SOURCE_DIR) + "/config/server.pbtxt";
  proto::ServerConfig config;
  ASSERT_TRUE(LoadServerConfig(path, &config).ok());
  ServerSetup setup;
  const Status loaded = MakeServerSetup(config, path, "", &setup);
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  ASSERT_NE(setup.scene, nullptr);
  setup.options.prefix = "D";
  setup.options.start_paused = true;
  SimServer server(setup.options, &transport_);
  ASSERT_TRUE(server.Init(setup.scene.get(), setup.method).ok());
  for (const auto& [shape, z] : {std::pair<int8_t, double>{body_cmd_t::SPHERE, 1.0}, {body_cmd_t::BOX, 2.0},
                                 {body_cmd_t::PLANE, -1.0}}) {
    const reply_t r = Send(server, protocol::kBodyCmd, Add(shape, z));
    ASSERT_EQ(r.code, reply_t::OK) << r.message;
  }
  scene_cmd_t method{};
  method.client_id = "default";
  method.op = scene_cmd_t::SET_METHOD;
  method.method = GetParam();
  reply_t r = Send(server, protocol::kSceneCmd, method);
  ASSERT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(server.method().Name(), GetParam());
  scene_cmd_t step{};
  step.client_id = "default";
  step.op = scene_cmd_t::STEP;
  step.steps = 1;
  const int64_t before = server.world().step;
  r = Send(server, protocol::kSceneCmd, step);
  EXPECT_EQ(r.code, reply_t::OK) << r.message;
  EXPECT_EQ(server.world().step, before + 1);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, SimServerDefaultWorldTest, ::testing::ValuesIn(ContactMethodNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace contactsim
