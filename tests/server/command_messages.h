// One valid message of every op of every command channel, encoded, for
// tests and fuzz seeds that start from good bytes and break them.
#pragma once

#include <contactsim/body_cmd_t.hpp>
#include <contactsim/input_t.hpp>
#include <contactsim/joint_cmd_t.hpp>
#include <contactsim/ray_cast_t.hpp>
#include <contactsim/scene_cmd_t.hpp>
#include <contactsim/sensor_cmd_t.hpp>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace contactsim {
namespace testing {

template <typename Msg>
std::string EncodeMessage(const Msg& m) {
  std::string bytes(m.getEncodedSize(), '\0');
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

struct SampleMessage {
  std::string suffix;  // the channel's suffix: "BODY_CMD", ...
  std::string label;   // "BODY_CMD ADD convex", ...
  std::string bytes;
};

inline std::vector<SampleMessage> SampleCommandMessages() {
  std::vector<SampleMessage> out;
  auto body = [&](int8_t op, int8_t shape, const std::string& label) {
    body_cmd_t m{};
    m.client_id = "sample";
    m.request_id = 7;
    m.op = op;
    m.body_id = 1;
    m.shape = shape;
    m.radius = 0.1;
    m.half_extents[0] = m.half_extents[1] = m.half_extents[2] = 0.1;
    m.half_length = 0.2;
    m.plane_normal[2] = 1.0;
    m.orientation[0] = 1.0;
    m.position[2] = 1.0;
    m.mass = op == body_cmd_t::SET_MASS ? 2.0 : 0.0;
    m.has_restitution = true;
    m.restitution = 0.5;
    m.impulse[0] = 1.0;
    m.duration = 0.1;
    if (shape == body_cmd_t::CONVEX) {
      m.points = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
      m.num_points = 4;
    }
    if (shape == body_cmd_t::COMPOUND) {  // a box and a hull beside it, with a link's inertial
      m.num_parts = 2;
      m.part_shape = {body_cmd_t::BOX, body_cmd_t::CONVEX};
      m.part_radius = {0.0, 0.0};
      m.part_half_extents = {{0.1, 0.1, 0.1}, {0, 0, 0}};
      m.part_half_length = {0.0, 0.0};
      m.part_num_points = {0, 4};
      m.num_part_points = 4;
      m.part_points = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
      m.part_position = {{0, 0, 0}, {0.2, 0, 0}};
      m.part_orientation = {{1, 0, 0, 0}, {0, 0, 0, 1}};
      m.mass = 2.0;
      m.has_center_of_mass = true;
      m.center_of_mass[0] = 0.05;
      m.has_inertia = true;
      const double inertia[6] = {0.02, 0.03, 0.025, 0.001, -0.002, 0.0005};
      std::copy(inertia, inertia + 6, m.inertia);
    }
    m.name = "b";
    out.push_back({"BODY_CMD", "BODY_CMD " + label, EncodeMessage(m)});
  };
  body(body_cmd_t::ADD, body_cmd_t::SPHERE, "ADD sphere");
  body(body_cmd_t::ADD, body_cmd_t::BOX, "ADD box");
  body(body_cmd_t::ADD, body_cmd_t::PLANE, "ADD plane");
  body(body_cmd_t::ADD, body_cmd_t::CAPSULE, "ADD capsule");
  body(body_cmd_t::ADD, body_cmd_t::CONVEX, "ADD convex");
  body(body_cmd_t::ADD, body_cmd_t::COMPOUND, "ADD compound");
  for (int8_t op = body_cmd_t::REMOVE; op <= body_cmd_t::SET_FILTER; ++op) {
    body(op, body_cmd_t::SPHERE, "op " + std::to_string(op));
  }
  for (int8_t op = scene_cmd_t::RESET; op <= scene_cmd_t::RELEASE_CONTROLLER; ++op) {
    scene_cmd_t m{};
    m.client_id = "sample";
    m.request_id = 8;
    m.op = op;
    m.path = op == scene_cmd_t::LOAD_SCENE ? "no/such/scene.pbtxt" : "";
    m.gravity[2] = -9.81;
    m.dt = 1.0 / 240.0;
    m.method = "lcp";
    m.param_names = {"solver"};
    m.param_values = {"pgs"};
    m.num_params = 1;
    m.steps = 3;
    m.mode = scene_cmd_t::FREE_RUN;
    m.real_time_factor = 1.0;
    m.name = op == scene_cmd_t::SNAPSHOT || op == scene_cmd_t::RESTORE ? "slot" : "";
    m.target_step = 2;
    out.push_back({"SCENE_CMD", "SCENE_CMD op " + std::to_string(op), EncodeMessage(m)});
  }
  for (int8_t op : {joint_cmd_t::ADD, joint_cmd_t::REMOVE}) {
    joint_cmd_t m{};
    m.client_id = "sample";
    m.request_id = 9;
    m.op = op;
    m.joint_id = 1;
    m.kind = joint_cmd_t::HINGE;
    m.body_a = 1;
    m.has_axis = true;
    m.axis[2] = 1.0;
    out.push_back({"JOINT_CMD", "JOINT_CMD op " + std::to_string(op), EncodeMessage(m)});
  }
  for (int8_t op = sensor_cmd_t::ADD_RANGE; op <= sensor_cmd_t::REMOVE; ++op) {
    sensor_cmd_t m{};
    m.client_id = "sample";
    m.request_id = 11;
    m.op = op;
    m.name = "lidar";
    m.body_id = 1;
    m.directions = {{1, 0, 0}, {0, 1, 0}};
    m.num_rays = 2;
    m.max_distance = 5.0;
    out.push_back({"SENSOR_CMD", "SENSOR_CMD op " + std::to_string(op), EncodeMessage(m)});
  }
  ray_cast_t rays{};
  rays.client_id = "sample";
  rays.request_id = 12;
  rays.origins = {{0, 0, 1}, {0, 0, 2}};
  rays.directions = {{0, 0, -1}, {1, 0, 0}};
  rays.max_distances = {5.0, 5.0};
  rays.num_rays = 2;
  rays.ignore_ids = {1};
  rays.num_ignore = 1;
  out.push_back({"RAY_CAST", "RAY_CAST", EncodeMessage(rays)});
  input_t in{};
  in.client_id = "sample";
  in.request_id = 10;
  in.step = 1;
  in.body_ids = {1, 2};
  in.forces = {{1, 0, 0}, {0, 1, 0}};
  in.torques = {{0, 0, 0}, {0, 0, 1}};
  in.num_bodies = 2;
  out.push_back({"INPUT", "INPUT", EncodeMessage(in)});
  return out;
}

}  // namespace testing
}  // namespace contactsim
