// Command half of contactsim::Client: turns typed calls into body_cmd_t /
// scene_cmd_t messages. No validation happens here on purpose: the server is
// the one gate for bad input (docs/protocol.md), and its error replies name
// the field, which a second client-side copy of the rules would only shadow.
#include <algorithm>

#include "contactsim/client.h"

#include "contactsim/protocol.hpp"

namespace contactsim {
namespace {

void Copy(const Eigen::Vector3d& from, double to[3]) {
  std::copy(from.data(), from.data() + 3, to);
}

// The wire carries the 32-bit sets as int32 bit patterns (LCM has no
// unsigned types).
void PutFilter(const CollisionFilter& filter, body_cmd_t* command) {
  command->collision_category = static_cast<int32_t>(filter.category);
  command->collision_mask = static_cast<int32_t>(filter.mask);
  command->collision_group = filter.group;
}

}  // namespace

body_cmd_t Client::NewBodyCommand(int8_t op, int64_t body_id) const {
  // lcm-gen types leave numbers uninitialised; {} zeroes every field.
  body_cmd_t command{};
  command.op = op;
  command.body_id = body_id;
  return command;
}

scene_cmd_t Client::NewSceneCommand(int8_t op) const {
  scene_cmd_t command{};
  command.op = op;
  return command;
}

CommandResult Client::Reset() {
  return Send(NewSceneCommand(scene_cmd_t::RESET));
}

CommandResult Client::LoadScene(const std::string& path) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::LOAD_SCENE);
  command.path = path;
  return Send(command);
}

CommandResult Client::SetGravity(const Eigen::Vector3d& gravity) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::SET_GRAVITY);
  Copy(gravity, command.gravity);
  return Send(command);
}

CommandResult Client::SetTimestep(double dt) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::SET_TIMESTEP);
  command.dt = dt;
  return Send(command);
}

CommandResult Client::SetContactMethod(
    const std::string& name, const std::map<std::string, std::string>& params) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::SET_METHOD);
  command.method = name;
  for (const auto& [key, value] : params) {
    command.param_names.push_back(key);
    command.param_values.push_back(value);
  }
  return Send(command);
}

CommandResult Client::Pause() {
  return Send(NewSceneCommand(scene_cmd_t::PAUSE));
}

CommandResult Client::Resume() {
  return Send(NewSceneCommand(scene_cmd_t::RESUME));
}

CommandResult Client::SetMode(Mode mode, double real_time_factor) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::SET_MODE);
  command.mode = static_cast<int8_t>(mode);
  command.real_time_factor = real_time_factor;
  return Send(command);
}

CommandResult Client::SaveSnapshot(const std::string& name) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::SNAPSHOT);
  command.name = name;
  return Send(command);
}

CommandResult Client::SaveSnapshotToFile(const std::string& path) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::SNAPSHOT);
  command.path = path;
  return Send(command);
}

CommandResult Client::Restore(const std::string& name) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::RESTORE);
  command.name = name;
  return Send(command);
}

CommandResult Client::RestoreFromFile(const std::string& path) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::RESTORE);
  command.path = path;
  return Send(command);
}

CommandResult Client::Rewind(int64_t step) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::REWIND);
  command.target_step = step;
  return Send(command);
}

CommandResult Client::RegisterController(LatePolicy policy, double late_timeout) {
  scene_cmd_t command = NewSceneCommand(scene_cmd_t::REGISTER_CONTROLLER);
  command.late_policy = static_cast<int8_t>(policy);
  command.late_timeout = late_timeout;
  return Send(command);
}

CommandResult Client::ReleaseController() {
  return Send(NewSceneCommand(scene_cmd_t::RELEASE_CONTROLLER));
}

int64_t Client::SendInput(int64_t step, const BodyInputs& inputs, int64_t request_id) {
  return SendInput(step, inputs, JointCommand{}, request_id);
}

int64_t Client::SendInput(int64_t step, const BodyInputs& inputs, const JointCommand& joints, int64_t request_id) {
  input_t message{};
  message.joints = EncodeJointCommand(joints);
  message.client_id = options_.client_id;
  message.request_id = request_id > 0 ? request_id : NextRequestId();
  message.step = step;
  for (const auto& [id, wrench] : inputs) {
    message.body_ids.push_back(id);
    message.forces.push_back({wrench.force.x(), wrench.force.y(), wrench.force.z()});
    message.torques.push_back({wrench.torque.x(), wrench.torque.y(), wrench.torque.z()});
  }
  message.num_bodies = static_cast<int32_t>(message.body_ids.size());
  std::vector<uint8_t> buffer(message.getEncodedSize());
  message.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  if (!PublishRaw(Channel(protocol::kInput), buffer.data(), static_cast<int>(buffer.size()))) return 0;
  return message.request_id;
}

CommandResult Client::AddBody(body_cmd_t command, const BodyOptions& options) {
  Copy(options.position, command.position);
  std::copy(options.orientation.begin(), options.orientation.end(),
            command.orientation);
  Copy(options.velocity, command.linear_velocity);
  Copy(options.angular_velocity, command.angular_velocity);
  command.mass = options.mass.value_or(0.0);
  command.density = options.density.value_or(0.0);
  command.has_restitution = options.restitution.has_value();
  command.restitution = options.restitution.value_or(0.0);
  command.has_friction = options.friction.has_value();
  command.friction = options.friction.value_or(0.0);
  command.fixed = options.fixed;
  command.kinematic = options.kinematic;
  command.name = options.name;
  command.has_center_of_mass = options.center_of_mass.has_value();
  if (options.center_of_mass) Copy(*options.center_of_mass, command.center_of_mass);
  command.has_inertia = options.inertia.has_value();
  if (options.inertia) {
    const Eigen::Matrix3d& i = *options.inertia;
    const double unique[6] = {i(0, 0), i(1, 1), i(2, 2), i(0, 1), i(0, 2), i(1, 2)};
    std::copy(unique, unique + 6, command.inertia);
  }
  command.has_filter = options.filter.has_value();
  PutFilter(options.filter.value_or(CollisionFilter{}), &command);
  return Send(command);
}

Result<int64_t> Client::AddSphere(double radius, const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::SPHERE;
  command.radius = radius;
  return WithNewId(AddBody(command, options));
}

Result<int64_t> Client::AddBox(const Eigen::Vector3d& half_extents,
                               const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::BOX;
  Copy(half_extents, command.half_extents);
  return WithNewId(AddBody(command, options));
}

Result<int64_t> Client::AddCapsule(double radius, double half_length,
                                   const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::CAPSULE;
  command.radius = radius;
  command.half_length = half_length;
  return WithNewId(AddBody(command, options));
}

Result<int64_t> Client::AddConvex(const std::vector<Eigen::Vector3d>& points,
                                  const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::CONVEX;
  for (const Eigen::Vector3d& p : points) {
    command.points.push_back({p.x(), p.y(), p.z()});
  }
  return WithNewId(AddBody(command, options));
}

Result<int64_t> Client::AddCompound(const std::vector<ShapePart>& parts,
                                    const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::COMPOUND;
  for (const ShapePart& part : parts) {
    command.part_shape.push_back(static_cast<int8_t>(part.type));
    command.part_radius.push_back(part.radius);
    command.part_half_extents.push_back(
        {part.half_extents.x(), part.half_extents.y(), part.half_extents.z()});
    command.part_half_length.push_back(part.half_length);
    command.part_num_points.push_back(static_cast<int32_t>(part.points.size()));
    for (const Eigen::Vector3d& p : part.points) {
      command.part_points.push_back({p.x(), p.y(), p.z()});
    }
    command.part_position.push_back({part.position.x(), part.position.y(), part.position.z()});
    command.part_orientation.push_back(
        {part.orientation[0], part.orientation[1], part.orientation[2], part.orientation[3]});
  }
  return WithNewId(AddBody(command, options));
}

Result<int64_t> Client::AddPlane(const Eigen::Vector3d& normal, double offset,
                                 const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::PLANE;
  Copy(normal, command.plane_normal);
  command.plane_offset = offset;
  // A plane has no pose, mass or velocity of its own; sending the caller's
  // defaults would only invite "plane made dynamic" errors.
  BodyOptions plane;
  plane.restitution = options.restitution;
  plane.friction = options.friction;
  plane.name = options.name;
  plane.filter = options.filter;
  plane.fixed = true;
  return WithNewId(AddBody(command, plane));
}

namespace {

// A static surface's options: its pose, material, name and filter; no
// mass or velocity of its own.
BodyOptions SurfaceOptions(const BodyOptions& options) {
  BodyOptions surface;
  surface.position = options.position;
  surface.orientation = options.orientation;
  surface.restitution = options.restitution;
  surface.friction = options.friction;
  surface.name = options.name;
  surface.filter = options.filter;
  surface.fixed = true;
  return surface;
}

}  // namespace

Result<int64_t> Client::AddMesh(const std::vector<Eigen::Vector3d>& vertices, const std::vector<int32_t>& indices,
                                double scale, const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::MESH;
  for (const Eigen::Vector3d& v : vertices) command.points.push_back({v.x(), v.y(), v.z()});
  command.mesh_indices = indices;
  command.mesh_scale = scale;
  return WithNewId(AddBody(command, SurfaceOptions(options)));
}

Result<int64_t> Client::AddMeshFile(const std::string& path, double scale, const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::MESH;
  command.mesh_path = path;
  command.mesh_scale = scale;
  return WithNewId(AddBody(command, SurfaceOptions(options)));
}

Result<int64_t> Client::AddHeightfield(int rows, int cols, const std::vector<double>& heights, double spacing_x,
                                       double spacing_y, const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::HEIGHTFIELD;
  command.height_rows = rows;
  command.height_cols = cols;
  command.heights = heights;
  command.height_spacing[0] = spacing_x;
  command.height_spacing[1] = spacing_y;
  return WithNewId(AddBody(command, SurfaceOptions(options)));
}

Result<int64_t> Client::AddHeightfieldFile(const std::string& path, double spacing_x, double spacing_y,
                                           const HeightMapOptions& map, const BodyOptions& options) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::ADD, 0);
  command.shape = body_cmd_t::HEIGHTFIELD;
  command.height_path = path;
  command.height_rows = map.rows;
  command.height_cols = map.cols;
  command.height_scale = map.scale;
  command.height_offset = map.offset;
  command.height_spacing[0] = spacing_x;
  command.height_spacing[1] = spacing_y;
  return WithNewId(AddBody(command, SurfaceOptions(options)));
}

CommandResult Client::RemoveBody(int64_t id) {
  return Send(NewBodyCommand(body_cmd_t::REMOVE, id));
}

CommandResult Client::SetPose(int64_t id, const Eigen::Vector3d& position,
                              const std::array<double, 4>& orientation) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::SET_POSE, id);
  Copy(position, command.position);
  std::copy(orientation.begin(), orientation.end(), command.orientation);
  return Send(command);
}

CommandResult Client::SetVelocity(int64_t id, const Eigen::Vector3d& velocity,
                                  const Eigen::Vector3d& angular_velocity) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::SET_VELOCITY, id);
  Copy(velocity, command.linear_velocity);
  Copy(angular_velocity, command.angular_velocity);
  return Send(command);
}

CommandResult Client::ApplyForce(int64_t id, const Eigen::Vector3d& force,
                                 const Eigen::Vector3d& torque,
                                 double duration) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::APPLY_FORCE, id);
  Copy(force, command.force);
  Copy(torque, command.torque);
  command.duration = duration;
  return Send(command);
}

CommandResult Client::ApplyImpulse(int64_t id, const Eigen::Vector3d& impulse,
                                   const std::optional<Eigen::Vector3d>& point) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::APPLY_IMPULSE, id);
  Copy(impulse, command.impulse);
  command.has_point = point.has_value();
  if (point) Copy(*point, command.point);
  return Send(command);
}

CommandResult Client::SetMass(int64_t id, double mass) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::SET_MASS, id);
  command.mass = mass;
  return Send(command);
}

CommandResult Client::SetDensity(int64_t id, double density) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::SET_MASS, id);
  command.density = density;
  return Send(command);
}

CommandResult Client::SetMaterial(int64_t id, std::optional<double> restitution,
                                  std::optional<double> friction) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::SET_MATERIAL, id);
  command.has_restitution = restitution.has_value();
  command.restitution = restitution.value_or(0.0);
  command.has_friction = friction.has_value();
  command.friction = friction.value_or(0.0);
  return Send(command);
}

CommandResult Client::SetFilter(int64_t id, const CollisionFilter& filter) {
  body_cmd_t command = NewBodyCommand(body_cmd_t::SET_FILTER, id);
  PutFilter(filter, &command);
  return Send(command);
}

}  // namespace contactsim
