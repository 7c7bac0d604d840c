// A server with an arm driver of either protocol and a hand-made seven-joint
// arm, for the arm driver's tests (arm_driver_test.cpp, panda_driver_test.cpp):
// a base and seven links in a horizontal line along x, each hinged to the
// one before about y, so that every joint carries the weight of the links
// beyond it and the hold torques are known in closed form.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "service/proto/model.pb.h"
#include "service/scene/model_proto.h"
#include "tests/model/hand_made_models.h"
#include "tests/server/server_harness.h"

namespace contactsim {
namespace testing {

constexpr double kArmG = 9.81;          // m/s^2, the world's default gravity
constexpr double kLinkPitch = 0.2;      // m between two joints of the chain
constexpr double kComOffset = 0.1;      // m from a link's joint to its centre of mass
inline double LinkMass(int k) { return 1.0 + 0.1 * k; }  // kg, link k = 1..7

inline model::ModelDescription Chain7() {
  using model::testing::Revolute;
  using model::testing::SphereLink;
  model::ModelDescription d;
  d.name = "chain";
  d.source = "<inline>";
  d.links.push_back(SphereLink("base", 2.0, 0.05, Vec3::Zero()));
  for (int k = 1; k <= kArmJoints; ++k) {
    const std::string link = "l" + std::to_string(k);
    d.links.push_back(SphereLink(link, LinkMass(k), 0.04, Vec3(kComOffset, 0, 0)));
    d.joints.push_back(Revolute("j" + std::to_string(k), k == 1 ? "base" : "l" + std::to_string(k - 1), link,
                                Vec3(k == 1 ? 0.0 : kLinkPitch, 0, 0), Vec3::UnitY()));
  }
  return d;
}

// A MODEL_CMD LOAD of Chain7 named "arm", on a fixed base 1 m up.
inline model_cmd_t LoadChain() {
  model_cmd_t m{};
  m.client_id = "test";
  m.op = model_cmd_t::LOAD;
  m.format = model_cmd_t::FORMAT_RESOLVED;
  proto::ModelDescription p;
  SaveModelDescription(Chain7(), &p);
  const std::string bytes = p.SerializeAsString();
  m.resolved.assign(bytes.begin(), bytes.end());
  m.name = "arm";
  m.position[2] = 1.0;
  m.orientation[0] = 1.0;
  m.fixed_base = true;
  return m;
}

// The torque joint i's drive needs to hold the horizontal chain (N m): the
// moment of the links beyond it, -sum m_k g (x_k - x_i) about +y.
inline double ChainHoldTorque(int i) {
  double tau = 0;
  for (int k = i + 1; k <= kArmJoints; ++k) tau -= LinkMass(k) * kArmG * ((k - 1 - i) * kLinkPitch + kComOffset);
  return tau;
}

// A server driving the model "arm" over `protocol` on Drake's channels and
// rate, with the given gains on every joint.
inline ServerOptions ArmOptions(const std::string& protocol, bool gravity_compensation = true,
                                double kp = kDefaultArmKp, double kd = kDefaultArmKd) {
  ServerOptions o;
  o.prefix = "A";
  ArmDriverConfig arm;
  arm.protocol = protocol;
  arm.model = "arm";
  arm.command_channel = DefaultArmCommandChannel(protocol);
  arm.status_channel = DefaultArmStatusChannel(protocol);
  arm.status_rate_hz = FindArmProtocol(protocol)->default_status_rate_hz;
  arm.kp.assign(kArmJoints, kp);
  arm.kd.assign(kArmJoints, kd);
  arm.gravity_compensation = gravity_compensation;
  o.arm_driver = arm;
  return o;
}

// One value per joint: base, base + 0.01, ...
inline std::vector<double> Targets(double base) {
  std::vector<double> v;
  for (int i = 0; i < kArmJoints; ++i) v.push_back(base + 0.01 * i);
  return v;
}

// The server with the chain loaded; `joints` are its hinges in order.
struct ArmServer {
  explicit ArmServer(ServerOptions o) : arm(*o.arm_driver), h(std::move(o)) {
    const reply_t r = h.Send(LoadChain());
    EXPECT_EQ(r.code, reply_t::OK) << r.message;
    joints.assign(r.ids.end() - kArmJoints, r.ids.end());
  }
  // Hands an encoded command to the server on the driver's command channel.
  template <typename Msg>
  void Post(const Msg& m) {
    const auto bytes = Encode(m);
    h.server.OnMessage(arm.command_channel, bytes.data(), static_cast<int>(bytes.size()));
  }
  const Joint& joint(int i) const { return *h.server.world().FindJoint(joints[i]); }
  std::vector<reply_t> Replies() const { return h.transport.All<reply_t>(h.server.Channel("REPLY")); }
  template <typename Msg>
  std::vector<Msg> Statuses() const {
    return h.transport.All<Msg>(arm.status_channel);
  }
  const ArmDriverConfig arm;
  ServerHarness h;
  std::vector<int64_t> joints;
};

}  // namespace testing
}  // namespace contactsim
