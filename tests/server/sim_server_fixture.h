// The server under test with a recording transport, without a network:
// typed builders for commands and a Send that delivers one and returns its
// reply.
#pragma once

#include <gtest/gtest.h>

#include <contactsim/body_cmd_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/reply_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/state_t.hpp>

#include <string>
#include <utility>
#include <vector>

#include "service/contact/contact_method_registry.h"
#include "service/server/command_decoder.h"
#include "service/server/sim_server.h"
#include "tests/server/recording_transport.h"

namespace contactsim {
namespace testing {

// The options of the servers under test: prefix "T", paused, free-running.
inline ServerOptions TestServerOptions() {
  ServerOptions o;
  o.prefix = "T";
  o.start_paused = true;
  o.mode = RunMode::kFreeRun;
  return o;
}

class SimServerTest : public ::testing::Test {
 protected:
  SimServerTest() : server_(Options(), &transport_) {
    std::shared_ptr<ContactMethod> method;
    EXPECT_TRUE(MakeContactMethod("impulse", {}, &method).ok());
    EXPECT_TRUE(server_.Init(nullptr, method).ok());
  }
  static ServerOptions Options() { return TestServerOptions(); }
  // Restitution 0.5, the server's default material when these tests were
  // written.
  body_cmd_t Sphere(double radius, const Vec3& p) {
    body_cmd_t m{};
    m.client_id = "test";
    m.request_id = ++request_id_;
    m.op = body_cmd_t::ADD;
    m.shape = body_cmd_t::SPHERE;
    m.radius = radius;
    for (int i = 0; i < 3; ++i) m.position[i] = p[i];
    m.orientation[0] = 1.0;
    m.num_points = 0;
    m.has_restitution = true;
    m.restitution = 0.5;
    return m;
  }
  scene_cmd_t Scene(int8_t op) {
    scene_cmd_t m{};
    m.client_id = "test";
    m.request_id = ++request_id_;
    m.op = op;
    m.num_params = 0;
    return m;
  }
  reply_t Send(const body_cmd_t& m) {
    const auto bytes = Encode(m);
    server_.OnMessage(server_.Channel("BODY_CMD"), bytes.data(), static_cast<int>(bytes.size()));
    server_.Tick();
    return transport_.All<reply_t>("T_REPLY").back();
  }
  reply_t Send(const scene_cmd_t& m) {
    const auto bytes = Encode(m);
    server_.OnMessage(server_.Channel("SCENE_CMD"), bytes.data(), static_cast<int>(bytes.size()));
    server_.Tick();
    return transport_.All<reply_t>("T_REPLY").back();
  }
  joint_cmd_t Joint(int8_t kind, int64_t a, int64_t b, const Vec3& anchor) {
    joint_cmd_t m{};
    m.client_id = "test";
    m.request_id = ++request_id_;
    m.op = joint_cmd_t::ADD;
    m.kind = kind;
    m.body_a = a;
    m.body_b = b;
    for (int i = 0; i < 3; ++i) m.anchor[i] = anchor[i];
    return m;
  }
  reply_t Send(const joint_cmd_t& m) {
    const auto bytes = Encode(m);
    server_.OnMessage(server_.Channel("JOINT_CMD"), bytes.data(), static_cast<int>(bytes.size()));
    server_.Tick();
    return transport_.All<reply_t>("T_REPLY").back();
  }

  RecordingTransport transport_;
  SimServer server_;
  int64_t request_id_ = 0;
};

}  // namespace testing
}  // namespace contactsim
