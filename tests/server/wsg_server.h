// A server with a WSG driver and a hand-made two-finger gripper, for the WSG
// driver's tests (wsg_driver_test.cpp): a palm on a fixed base 1 m up and
// two box fingers on prismatic joints along x, in Drake's WSG convention:
// the left finger opens to q < 0, the right to q > 0, and at q = 0 their
// inner faces meet at the palm's centre, so the separation is q_1 - q_0.
#pragma once

#include <gtest/gtest.h>

#include <drake/lcmt_schunk_wsg_command.hpp>
#include <drake/lcmt_schunk_wsg_status.hpp>

#include <string>
#include <vector>

#include "service/proto/model.pb.h"
#include "service/scene/model_proto.h"
#include "tests/server/server_harness.h"

namespace contactsim {
namespace testing {

constexpr double kStroke = 0.055;        // m, each finger's opening, the WSG 50's (110 mm in all)
constexpr double kFingerEffort = 80;     // N, the joints' <limit effort>, the WSG 50's largest grip force
constexpr double kFingerWidth = 0.01;    // m along x
constexpr double kFingerMass = 0.1;      // kg

inline model::Link BoxLink(const std::string& name, double mass, const Vec3& size, const Vec3& centre) {
  model::Link l;
  l.name = name;
  model::Inertial in;
  in.mass = mass;
  in.origin.position = centre;
  const Vec3 s2 = size.cwiseProduct(size);
  in.inertia = (mass / 12.0 * Vec3(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
  l.inertial = in;
  model::CollisionElement c;
  c.origin.position = centre;
  c.geometry.type = model::GeometryType::kBox;
  c.geometry.box_size = size;
  l.collisions.push_back(c);
  return l;
}

inline model::ModelJoint Finger(const std::string& name, const std::string& child, double lower, double upper) {
  model::ModelJoint j;
  j.name = name;
  j.type = model::JointType::kPrismatic;
  j.parent = "palm";
  j.child = child;
  j.axis = Vec3::UnitX();
  j.limits = model::JointLimits{lower, upper, kFingerEffort, 0.5};
  return j;
}

inline model::ModelDescription TwoFingerGripper() {
  model::ModelDescription d;
  d.name = "gripper";
  d.source = "<inline>";
  // the palm's collision box sits 0.1 m above the fingers, clear of them and
  // of an object held between them
  d.links.push_back(BoxLink("palm", 1.0, Vec3(0.15, 0.05, 0.02), Vec3(0, 0, 0.1)));
  const Vec3 finger(kFingerWidth, 0.02, 0.06);
  d.links.push_back(BoxLink("left", kFingerMass, finger, Vec3(-kFingerWidth / 2, 0, 0)));
  d.links.push_back(BoxLink("right", kFingerMass, finger, Vec3(kFingerWidth / 2, 0, 0)));
  d.joints.push_back(Finger("left_finger_sliding_joint", "left", -kStroke, 0));
  d.joints.push_back(Finger("right_finger_sliding_joint", "right", 0, kStroke));
  return d;
}

// A MODEL_CMD LOAD of the gripper, on a fixed base 1 m up.
inline model_cmd_t LoadGripper() {
  model_cmd_t m{};
  m.client_id = "test";
  m.op = model_cmd_t::LOAD;
  m.format = model_cmd_t::FORMAT_RESOLVED;
  proto::ModelDescription p;
  SaveModelDescription(TwoFingerGripper(), &p);
  const std::string bytes = p.SerializeAsString();
  m.resolved.assign(bytes.begin(), bytes.end());
  m.name = "gripper";
  m.position[2] = 1.0;
  m.orientation[0] = 1.0;
  m.fixed_base = true;
  return m;
}

// A server driving the gripper's fingers on Drake's channels and rate.
inline ServerOptions WsgOptions() {
  ServerOptions o;
  o.prefix = "W";
  WsgDriverConfig w;
  w.model = "gripper";
  w.finger_joints[0] = "left_finger_sliding_joint";
  w.finger_joints[1] = "right_finger_sliding_joint";
  w.command_channel = kDefaultWsgCommandChannel;
  w.status_channel = kDefaultWsgStatusChannel;
  w.status_rate_hz = kDefaultWsgStatusRateHz;
  w.kp = kDefaultWsgKp;
  w.kd = kDefaultWsgKd;
  o.wsg_driver = w;
  return o;
}

inline drake::lcmt_schunk_wsg_command WsgCommandMsg(int64_t utime, double target_position_mm, double force) {
  drake::lcmt_schunk_wsg_command m;
  m.utime = utime;
  m.target_position_mm = target_position_mm;
  m.force = force;
  return m;
}

// The server with the gripper loaded; `fingers` are its two joints.
struct WsgServer {
  explicit WsgServer(ServerOptions o) : wsg(*o.wsg_driver), h(std::move(o)) {
    const reply_t r = h.Send(LoadGripper());
    EXPECT_EQ(r.code, reply_t::OK) << r.message;
    fingers.assign(r.ids.end() - 2, r.ids.end());
  }
  void Post(const drake::lcmt_schunk_wsg_command& m) {
    const auto bytes = Encode(m);
    h.server.OnMessage(wsg.command_channel, bytes.data(), static_cast<int>(bytes.size()));
  }
  const Joint& finger(int i) const { return *h.server.world().FindJoint(fingers[i]); }
  // The replies to the driver's commands.
  std::vector<reply_t> Replies() const {
    std::vector<reply_t> mine;
    for (const reply_t& r : h.transport.All<reply_t>(h.server.Channel("REPLY"))) {
      if (r.client_id == wsg.command_channel) mine.push_back(r);
    }
    return mine;
  }
  std::vector<drake::lcmt_schunk_wsg_status> Statuses() const {
    return h.transport.All<drake::lcmt_schunk_wsg_status>(wsg.status_channel);
  }
  const WsgDriverConfig wsg;
  ServerHarness h;
  std::vector<int64_t> fingers;
};

}  // namespace testing
}  // namespace contactsim
