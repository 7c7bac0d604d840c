// A SimServer on a recording transport with helpers that send commands the
// way the LCM thread does and tick the simulation thread by hand.
#pragma once

#include <gtest/gtest.h>

#include <contactsim/actuator_cmd_t.hpp>
#include <contactsim/body_cmd_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/model_cmd_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/scene_cmd_t.hpp>

#include <memory>
#include <string>

#include "service/contact/contact_method_registry.h"
#include "service/server/command_decoder.h"
#include "service/server/sim_server.h"
#include "tests/server/recording_transport.h"

namespace contactsim {
namespace testing {

class ServerHarness {
 public:
  explicit ServerHarness(ServerOptions options, const std::string& method = "impulse")
      : server(Paused(std::move(options)), &transport) {
    std::shared_ptr<ContactMethod> m;
    EXPECT_TRUE(MakeContactMethod(method, {}, &m).ok()) << method;
    const Status st = server.Init(nullptr, m);
    EXPECT_TRUE(st.ok()) << st.message();
  }
  static ServerOptions Paused(ServerOptions o) {
    o.start_paused = true;
    o.mode = RunMode::kFreeRun;
    return o;
  }

  // An ADD gives restitution 0.5, the server's default material when these
  // tests and their pinned hashes were written.
  body_cmd_t Body(int8_t op, int64_t id = 0) {
    body_cmd_t m{};
    m.client_id = "test";
    m.op = op;
    m.body_id = id;
    m.orientation[0] = 1.0;
    m.has_restitution = op == body_cmd_t::ADD;
    m.restitution = m.has_restitution ? 0.5 : 0.0;
    return m;
  }
  body_cmd_t Box(double half, const Vec3& p, const Vec3& v = Vec3::Zero()) {
    body_cmd_t m = Body(body_cmd_t::ADD);
    m.shape = body_cmd_t::BOX;
    for (int i = 0; i < 3; ++i) m.half_extents[i] = half, m.position[i] = p[i], m.linear_velocity[i] = v[i];
    return m;
  }
  scene_cmd_t Scene(int8_t op) {
    scene_cmd_t m{};
    m.client_id = "test";
    m.op = op;
    return m;
  }
  // Hands the command to the server and ticks once (applying it); returns
  // the reply.
  template <typename Msg>
  reply_t Send(Msg m) {
    Post(m);
    server.Tick();
    return transport.All<reply_t>(server.Channel("REPLY")).back();
  }
  // Hands the command to the server without ticking.
  void Post(body_cmd_t& m) {
    m.request_id = ++request_id;
    const auto bytes = Encode(m);
    server.OnMessage(server.Channel("BODY_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  }
  void Post(scene_cmd_t& m) {
    m.request_id = ++request_id;
    const auto bytes = Encode(m);
    server.OnMessage(server.Channel("SCENE_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  }
  void Post(joint_cmd_t& m) {
    m.request_id = ++request_id;
    const auto bytes = Encode(m);
    server.OnMessage(server.Channel("JOINT_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  }
  void Post(model_cmd_t& m) {
    m.request_id = ++request_id;
    m.resolved_size = static_cast<int32_t>(m.resolved.size());
    const auto bytes = Encode(m);
    server.OnMessage(server.Channel("MODEL_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  }
  void Post(actuator_cmd_t& m) {
    m.request_id = ++request_id;
    const auto bytes = Encode(m);
    server.OnMessage(server.Channel("ACTUATOR_CMD"), bytes.data(), static_cast<int>(bytes.size()));
  }
  void Post(input_t& m) {
    m.request_id = ++request_id;
    m.num_bodies = static_cast<int32_t>(m.body_ids.size());
    const auto bytes = Encode(m);
    server.OnMessage(server.Channel("INPUT"), bytes.data(), static_cast<int>(bytes.size()));
  }
  // STEP n, ticking until the server pauses again; the hash after each step.
  std::vector<uint64_t> Step(int n) {
    scene_cmd_t m = Scene(scene_cmd_t::STEP);
    m.steps = n;
    Post(m);
    std::vector<uint64_t> hashes;
    while (server.Tick()) hashes.push_back(HashWorldState(server.world()));
    return hashes;
  }

  RecordingTransport transport;
  SimServer server;
  int64_t request_id = 0;
};

}  // namespace testing
}  // namespace contactsim
